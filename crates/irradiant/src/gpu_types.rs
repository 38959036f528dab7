//! Every GPU struct of Irradiant, from the module that owns it, and their expected layouts
//! for the check against WGSL (`tests/gpu_structs.rs`). Each struct has one definition, beside
//! the code that uses it; this module only gathers them.

use irradiant_gpu::{Expected, gpu_layout};

pub use crate::ddgi::types::*;
pub use crate::frame::types::*;
pub use crate::lightfield::types::*;
pub use crate::pathtrace::types::*;
pub use crate::raycast::types::*;
pub use crate::scene::types::*;
pub use crate::ssil::types::*;

/// Every GPU struct with its expected layout, for the WGSL check.
pub fn all_layouts() -> Vec<Expected> {
    vec![
        gpu_layout!(GpuBvhNode {
            a_min,
            a_first,
            a_max,
            a_count,
            b_min,
            b_first,
            b_max,
            b_count
        }),
        gpu_layout!(GpuWideBvhNode {
            origin,
            exponents_imask,
            child_base,
            primitive_base,
            child_meta,
            q_min_x,
            q_max_x,
            q_min_y,
            q_max_y,
            q_min_z,
            q_max_z
        }),
        gpu_layout!(GpuTriangle {
            v0,
            material,
            e1,
            flags,
            e2,
            _pad
        }),
        gpu_layout!(GpuTriangleShading {
            n0,
            emitter_ordinal,
            n1,
            _pad1,
            n2,
            _pad2,
            uv0,
            uv1,
            uv2,
            _pad3
        }),
        gpu_layout!(GpuInstance {
            world_to_object0,
            world_to_object1,
            world_to_object2,
            object_to_world0,
            object_to_world1,
            object_to_world2,
            previous_object_to_world0,
            previous_object_to_world1,
            previous_object_to_world2,
            blas_root,
            emitter_base,
            _pad1,
            _pad2
        }),
        gpu_layout!(GpuMaterial {
            base_color,
            emission,
            texture,
            metallic,
            roughness,
            specular,
            alpha_cutoff
        }),
        gpu_layout!(GpuLight {
            position,
            kind,
            direction,
            cos_inner,
            power,
            cos_outer
        }),
        gpu_layout!(GpuEmitter {
            v0,
            triangle,
            e1,
            instance,
            e2,
            cluster,
            normal,
            _pad,
            radiance,
            pdf_area
        }),
        gpu_layout!(GpuSceneInfo {
            sky,
            light_count,
            emitter_count,
            grid_clusters,
            tlas_root,
            instance_count,
            grid_min,
            grid_width,
            grid_inverse_cell,
            grid_member_row,
            grid_dims,
            _pad
        }),
        gpu_layout!(GpuCamera {
            position,
            tan_half_fov_y,
            right,
            aspect,
            up,
            _pad0,
            forward,
            _pad1
        }),
        gpu_layout!(GpuPathTraceParams {
            camera,
            width,
            height,
            sample_offset,
            samples,
            max_bounces,
            seed,
            light_sampling,
            _pad1
        }),
        gpu_layout!(GpuGatherQuery {
            origin,
            far,
            axis,
            exponent,
            kind,
            on_surface,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuGatherParams {
            count,
            sample_offset,
            samples,
            max_bounces,
            seed,
            light_sampling,
            _pad1,
            _pad2
        }),
        gpu_layout!(GpuRay {
            origin,
            t_max,
            dir,
            stop
        }),
        gpu_layout!(GpuRayHit {
            t,
            triangle,
            instance,
            work
        }),
        gpu_layout!(GpuRayCastParams {
            ray_count,
            any_hit,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuFrameParams {
            camera,
            previous_camera,
            width,
            height,
            frame_index,
            area_light_samples,
            seed,
            accumulated_frames,
            jitter,
            taa_blend,
            history_frames,
            taa_clip_sigma,
            exposure,
            tone_curve,
            pyramid_pixel_sigma,
            pyramid_normal_sigma,
            pyramid_depth_sigma,
            emitter_candidates,
            reservoir_history,
            reuse_neighbours,
            reuse_radius,
            reuse_visibility,
            cut_candidates,
            cut_neighbours,
            direct_in_reuse,
            pick_sequence
        }),
        gpu_layout!(GpuDdgiVolume {
            origin,
            probe_count,
            spacing,
            rays_per_probe,
            counts,
            probes_per_row,
            ray_rotation0,
            ray_rotation1,
            ray_rotation2,
            irradiance_texels,
            distance_texels,
            irradiance_hysteresis,
            distance_hysteresis,
            max_ray_distance,
            self_shadow_bias,
            distance_exponent,
            irradiance_gamma,
            weights,
            frame,
            min_spacing,
            convergence_heuristics,
            relocating,
            all_lights,
            state_phase,
            wake_box_count,
            volume_index,
            volume_is_last,
            bounce_hysteresis,
            extrapolation,
            tied_probe_weight,
            every_probe_updates,
            shade_probes_in_geometry,
            gather_history_frames,
            gather_interval,
            phase_x,
            phase_y,
            phase_z,
            entering_start,
            entering_end,
            blend_centre,
            convergence_rounds,
            light_between_volumes,
            padding1,
            padding2
        }),
        gpu_layout!(GpuDdgiRayHit {
            t,
            triangle,
            instance,
            bary
        }),
        gpu_layout!(GpuDdgiRaySample { radiance, distance }),
        gpu_layout!(GpuDdgiBlendWeight { ray, weight }),
        gpu_layout!(GpuDdgiDeferredRead {
            position,
            viewer_distance,
            normal,
            geometric_normal,
            wo,
            weight_rg,
            weight_b_taken
        }),
        gpu_layout!(GpuDdgiShadowRay {
            origin,
            sample,
            contribution,
            light
        }),
        gpu_layout!(GpuSsilParams {
            start_level,
            levels,
            samples,
            visibility,
            radius,
            near,
            far,
            visibility_steps,
            visibility_bias,
            importance_alpha,
            hysteresis,
            motion_pixels,
            depth_tolerance,
            normal_tolerance,
            history_frames,
            hybrid,
            reach,
            glossy_above,
            _pad1,
            _pad2
        }),
        gpu_layout!(GpuSsilPass {
            level,
            first,
            last_bounce,
            radiance_level,
            coarse_level,
            with_gather,
            _pad0,
            _pad1
        }),
        gpu_layout!(GpuLightfieldParams {
            origin,
            probe_count,
            spacing,
            resolution,
            counts,
            low_resolution,
            min_thickness,
            max_thickness,
            thickness_distance,
            max_probe_visits,
            max_distance,
            prefilter_resolution,
            emitter_samples,
            bounce,
            algorithm,
            lambert_rays,
            glossy_rays,
            frame,
            lambert_hysteresis,
            glossy_hysteresis,
            history_valid,
            irradiance_block,
            glossy_max_roughness,
            _pad0,
            _pad1,
            _pad2
        }),
        gpu_layout!(GpuLightfieldFilterPass {
            direction,
            radius,
            stride
        }),
        gpu_layout!(GpuLightfieldHit {
            result,
            t,
            probe,
            visits
        }),
    ]
}
