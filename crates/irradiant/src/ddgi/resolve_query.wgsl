// ddgi/resolve's light at a pixel (`pixel_light`) without the final gather: the query.
#import ddgi_query

fn pixel_light(s: Surface, pixel: vec2<u32>, tile: vec2<u32>, local_index: u32) -> vec3<f32> {
    return ddgi_irradiance(s.position, s.normal, view_dir(s.position)).irradiance;
}
