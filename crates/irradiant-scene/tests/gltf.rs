//! glTF 2.0 loading: node hierarchy, materials (emissive strength, alpha mask, metallic-
//! roughness), KHR_lights_punctual and cameras, from .gltf (embedded buffer) and .glb.

use base64::prelude::{BASE64_STANDARD, Engine};
use glam::Vec3;
use irradiant_scene::{AlphaMode, LightKind, load};

/// One triangle: positions (36 bytes) then indices (3 × u16, padded to 8).
fn buffer() -> Vec<u8> {
    let mut bytes = Vec::new();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    bytes
}

fn document(buffer_uri: Option<String>, length: usize) -> String {
    let uri = buffer_uri
        .map(|u| format!(r#""uri": "{u}","#))
        .unwrap_or_default();
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "color": [1, 0.5, 0.25], "intensity": 20, "name": "bulb"}},
    {{"type": "spot", "intensity": 5, "spot": {{"innerConeAngle": 0.2, "outerConeAngle": 0.5}}}}
  ]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 3, 4]}}],
  "nodes": [
    {{"name": "parent", "translation": [10, 0, 0], "children": [1, 2]}},
    {{"name": "child", "mesh": 0, "translation": [0, 5, 0]}},
    {{"name": "lamp", "translation": [0, 2, 0], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
    {{"name": "cone", "rotation": [-0.7071068, 0, 0, 0.7071068], "translation": [0, 3, 0], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
    {{"name": "eye", "camera": 0, "translation": [0, 1, 7]}}
  ],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}}]}}],
  "materials": [{{
    "name": "glowing-leaf",
    "pbrMetallicRoughness": {{"baseColorFactor": [0.2, 0.4, 0.6, 1.0], "metallicFactor": 0.3, "roughnessFactor": 0.7}},
    "emissiveFactor": [1, 0.5, 0],
    "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": 4.0}}}},
    "alphaMode": "MASK", "alphaCutoff": 0.3
  }}],
  "buffers": [{{{uri} "byteLength": {length}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 6}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}}
  ]
}}"#
    )
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

fn check(path: &std::path::Path) {
    let loaded = load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
    let s = loaded.scene;
    assert_eq!(s.meshes.len(), 1);
    assert_eq!(s.instances.len(), 1);
    // The child's world position composes the parent's translation.
    let p = s.instances[0]
        .transform
        .transform_point3(Vec3::new(1.0, 0.0, 0.0));
    assert!((p - Vec3::new(11.0, 5.0, 0.0)).length() < 1e-5, "{p}");
    let m = &s.materials[0];
    assert_eq!(m.name, "glowing-leaf");
    assert!(
        (m.emission - Vec3::new(4.0, 2.0, 0.0)).length() < 1e-6,
        "emissive strength applied: {:?}",
        m.emission
    );
    assert!((m.metallic - 0.3).abs() < 1e-6 && (m.roughness - 0.7).abs() < 1e-6);
    assert_eq!(m.alpha_mode, AlphaMode::Mask { cutoff: 0.3 });
    let bulb = s.lights.iter().find(|l| l.name == "bulb").unwrap();
    assert_eq!(bulb.kind, LightKind::Point);
    assert!((bulb.position - Vec3::new(10.0, 2.0, 0.0)).length() < 1e-5);
    assert!((bulb.power() - Vec3::new(20.0, 10.0, 5.0)).length() < 1e-4);
    let spot = s
        .lights
        .iter()
        .find(|l| matches!(l.kind, LightKind::Spot { .. }))
        .unwrap();
    // Rotated −90° about x, the spot's −z axis points down.
    assert!(
        (spot.direction - Vec3::new(0.0, -1.0, 0.0)).length() < 1e-4,
        "{:?}",
        spot.direction
    );
    assert!((s.camera.position - Vec3::new(0.0, 1.0, 7.0)).length() < 1e-5);
    assert!((s.camera.fov_y_degrees - 0.8f32.to_degrees()).abs() < 1e-3);
    assert!(
        (s.camera.target - s.camera.position)
            .normalize()
            .dot(-Vec3::Z)
            > 0.999
    );
}

#[test]
fn gltf_with_embedded_buffer_and_glb_load_the_same_scene() {
    let dir = std::env::temp_dir().join(format!("irradiant-gltf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let data = buffer();
    let gltf_path = dir.join("scene.gltf");
    std::fs::write(
        &gltf_path,
        document(
            Some(format!(
                "data:application/octet-stream;base64,{}",
                BASE64_STANDARD.encode(&data)
            )),
            data.len(),
        ),
    )
    .unwrap();
    check(&gltf_path);
    let glb_path = dir.join("scene.glb");
    std::fs::write(&glb_path, glb(&document(None, data.len()), &data)).unwrap();
    check(&glb_path);
}
