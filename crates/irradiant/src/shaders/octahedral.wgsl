// Octahedral mapping of the unit sphere onto [-1, 1]² (Cigolle et al. 2014), as the DDGI and
// light-field probe atlases store directions. The CPU twin is ddgi::octahedral (tests).

fn sign_not_zero2(v: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(-1.0), vec2<f32>(1.0), v >= vec2<f32>(0.0));
}

fn oct_encode(n: vec3<f32>) -> vec2<f32> {
    let p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return select(p, (1.0 - abs(p.yx)) * sign_not_zero2(p), n.z < 0.0);
}

fn oct_decode(p: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(p, 1.0 - abs(p.x) - abs(p.y));
    if n.z < 0.0 {
        n = vec3<f32>((1.0 - abs(n.yx)) * sign_not_zero2(n.xy), n.z);
    }
    return normalize(n);
}

// Spherical Fibonacci point i of n: an almost uniform set of directions.
fn spherical_fibonacci(i: f32, n: f32) -> vec3<f32> {
    let phi = 6.28318530717959 * fract(i * 0.618033988749895);
    let cos_theta = 1.0 - (2.0 * i + 1.0) / n;
    let sin_theta = sqrt(saturate(1.0 - cos_theta * cos_theta));
    return vec3<f32>(cos(phi) * sin_theta, sin(phi) * sin_theta, cos_theta);
}
