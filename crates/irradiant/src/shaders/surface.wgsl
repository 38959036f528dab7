// Everything shading needs at a hit point, in world space.
struct Surface {
    position: vec3<f32>,
    // Geometric and shading normals, both turned towards the incoming ray (surfaces are
    // two-sided for reflection).
    geometric_normal: vec3<f32>,
    normal: vec3<f32>,
    albedo: vec3<f32>,
    metallic: f32,
    roughness: f32,
    specular: f32,
    // Emitted radiance towards the ray; emitters emit from their front (counter-clockwise) side.
    emission: vec3<f32>,
}
