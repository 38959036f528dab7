// The one BRDF of Irradiant, shared by the path tracer and every technique: Lambert diffuse
// plus a GGX microfacet specular lobe (metallic-roughness, as glTF), Smith height-correlated
// masking, Schlick Fresnel, visible-normal sampling (Heitz 2018).
#import sampling
#import scene

fn f0_of(s: Surface) -> vec3<f32> {
    return mix(vec3<f32>(0.04 * s.specular), s.albedo, s.metallic);
}

fn has_specular(s: Surface) -> bool {
    return s.specular > 0.0 || s.metallic > 0.0;
}

fn fresnel_schlick(f0: vec3<f32>, cos_theta: f32) -> vec3<f32> {
    return f0 + (1.0 - f0) * pow(1.0 - saturate(cos_theta), 5.0);
}

fn ggx_d(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / max(PI * d * d, 1e-30);
}

fn smith_lambda(cos_theta: f32, alpha: f32) -> f32 {
    let c2 = max(cos_theta * cos_theta, 1e-12);
    return 0.5 * (sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2) - 1.0);
}

fn diffuse_weight(s: Surface) -> vec3<f32> {
    // The specular layer takes its reflectance at normal incidence off the diffuse layer.
    return s.albedo * (1.0 - s.metallic) * (1.0 - 0.04 * s.specular);
}

// The share of what a surface reflects that its diffuse layer sends every way, by the layers'
// reflectance at normal incidence: 1 for Lambertian (and black) surfaces, 0 for metals.
fn diffuse_share(s: Surface) -> f32 {
    let diff = luminance(diffuse_weight(s));
    let spec = select(0.0, luminance(f0_of(s)), has_specular(s));
    return select(1.0, diff / (diff + spec), diff + spec > 0.0);
}

// Probability of sampling the specular lobe rather than the diffuse one.
fn specular_probability(s: Surface, n_dot_v: f32) -> f32 {
    if !has_specular(s) {
        return 0.0;
    }
    let spec = luminance(fresnel_schlick(f0_of(s), n_dot_v));
    let diff = luminance(diffuse_weight(s));
    return clamp(spec / max(spec + diff, 1e-6), 0.1, 1.0);
}

// f(wo, wi) (without the cosine) in world space; wo and wi point away from the surface.
fn brdf_eval(s: Surface, wo: vec3<f32>, wi: vec3<f32>) -> vec3<f32> {
    let n_dot_l = dot(s.normal, wi);
    let n_dot_v = dot(s.normal, wo);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return vec3<f32>(0.0);
    }
    var f = diffuse_weight(s) / PI;
    if has_specular(s) {
        let alpha = s.roughness * s.roughness;
        let h = normalize(wo + wi);
        let g2 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha) + smith_lambda(n_dot_l, alpha));
        let fr = fresnel_schlick(f0_of(s), dot(wo, h));
        f += fr * ggx_d(dot(s.normal, h), alpha) * g2 / (4.0 * n_dot_l * n_dot_v);
    }
    return f;
}

// The pdf (solid angle) with which brdf_sample picks wi.
fn brdf_pdf(s: Surface, wo: vec3<f32>, wi: vec3<f32>) -> f32 {
    let n_dot_l = dot(s.normal, wi);
    let n_dot_v = dot(s.normal, wo);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return 0.0;
    }
    let p_spec = specular_probability(s, n_dot_v);
    var pdf = (1.0 - p_spec) * n_dot_l / PI;
    if p_spec > 0.0 {
        let alpha = s.roughness * s.roughness;
        let h = normalize(wo + wi);
        let g1 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha));
        pdf += p_spec * g1 * ggx_d(dot(s.normal, h), alpha) / (4.0 * n_dot_v);
    }
    return pdf;
}

// A GGX visible normal about +z for a view direction v about +z (Heitz 2018).
fn sample_ggx_vndf(v: vec3<f32>, alpha: f32, u: vec2<f32>) -> vec3<f32> {
    let vh = normalize(vec3<f32>(alpha * v.x, alpha * v.y, v.z));
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(-vh.y, vh.x, 0.0) / sqrt(len2), len2 > 0.0);
    let t2 = cross(vh, t1);
    let r = sqrt(u.x);
    let phi = TAU * u.y;
    let p1 = r * cos(phi);
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * r * sin(phi);
    let nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3<f32>(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0)));
}

struct BrdfSample {
    dir: vec3<f32>,
    pdf: f32,
    // f · cos / pdf
    weight: vec3<f32>,
}

fn brdf_sample(s: Surface, wo: vec3<f32>, u_lobe: f32, u: vec2<f32>) -> BrdfSample {
    var out: BrdfSample;
    let frame = basis(s.normal);
    let n_dot_v = dot(s.normal, wo);
    let p_spec = specular_probability(s, n_dot_v);
    if u_lobe < p_spec {
        let alpha = s.roughness * s.roughness;
        let v_local = transpose(frame) * wo;
        let h = frame * sample_ggx_vndf(v_local, alpha, u);
        out.dir = reflect(-wo, h);
    } else {
        out.dir = frame * cosine_hemisphere(u);
    }
    out.pdf = brdf_pdf(s, wo, out.dir);
    let cos_l = dot(s.normal, out.dir);
    if out.pdf <= 0.0 || cos_l <= 0.0 {
        out.weight = vec3<f32>(0.0);
        out.pdf = 0.0;
    } else {
        out.weight = brdf_eval(s, wo, out.dir) * cos_l / out.pdf;
    }
    return out;
}
