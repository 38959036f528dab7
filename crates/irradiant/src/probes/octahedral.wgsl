// Octahedral mapping of the unit sphere onto [-1, 1]² (Cigolle et al. 2014), as the DDGI and
// light-field probe atlases store directions. The CPU twin is probes::octahedral.

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
