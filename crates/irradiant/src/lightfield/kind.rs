//! The registry entries `lightfield`, `lightfield-traced` and `lightfield-naive`: one kind a
//! shading algorithm, with what each allocates, dispatches and is built from.

// The technique's own types, constants and imports, from the folder's mod.rs.
use super::*;

/// A registry entry of light-field probes: the bake is shared, the shading algorithm differs.
pub struct LightfieldKind {
    pub(super) algorithm: ShadingAlgorithm,
}

impl LightfieldKind {
    /// The settings a spec asks for, with this entry's shading algorithm.
    pub fn settings(
        &self,
        spec: &TechniqueSpec,
        warnings: &mut Vec<String>,
    ) -> Result<LightfieldSettings, RenderError> {
        Ok(LightfieldSettings::from_spec(
            spec,
            self.algorithm,
            warnings,
        )?)
    }
}

/// The probe grid the settings ask for: the scene's first probe volume (or the default one
/// over its bounds); with the bake's own probe counts, that many probes at the centres of as
/// many equal cells of the volume's box (or the scene's bounds), so that a coarse grid keeps
/// its probes off the walls the box touches.
pub fn grid_of(scene: &Scene, settings: &LightfieldSettings) -> Result<ProbeGrid, RenderError> {
    let mut desc = crate::probes::volumes_of(scene).remove(0);
    let counts = settings.bake.probe_counts;
    if counts != [0, 0, 0] {
        let (lo, hi) = match scene.probe_volumes.first() {
            Some(v) => (v.min, v.max),
            None => scene.bounds(),
        };
        let extent = (hi - lo).max(Vec3::splat(1e-3));
        let inset = extent / glam::UVec3::from(counts).as_vec3() * 0.5;
        desc.min = lo + inset;
        desc.max = hi - inset;
        desc.counts = counts;
    }
    let grid = ProbeGrid::new(&desc);
    if grid.probe_count > MAX_PROBES {
        return Err(RenderError::Settings(format!(
            "technique.bake.probe_counts: {} probes are more than one bake dispatch holds ({MAX_PROBES}); use fewer probes",
            grid.probe_count
        )));
    }
    Ok(grid)
}

fn map_groups(side: u32, probes: u32) -> Workgroups {
    Workgroups::for_layers(side, side, probes, MAP_TILE)
}

/// The bake's dispatches, each with its label, in order.
pub(super) fn bake_dispatches(
    grid: &ProbeGrid,
    s: &LightfieldSettings,
) -> Vec<(&'static str, Workgroups)> {
    let b = &s.bake;
    let probes = grid.probe_count;
    let tile = b.irradiance_texels.max(b.distance_texels) + 2;
    let geometry = (BAKE[0], map_groups(b.resolution, probes));
    let per_probe = Workgroups::linear(probes as u64);
    let mut all = vec![geometry];
    for _ in 0..b.relocation_steps {
        all.extend([(BAKE[1], per_probe), geometry]);
    }
    all.extend([
        (BAKE[2], map_groups(b.resolution / MIN_MIP_FACTOR, probes)),
        (BAKE[3], per_probe),
    ]);
    for _ in 0..=b.bounces {
        all.extend([
            (BAKE[4], map_groups(b.resolution, probes)),
            (BAKE[5], map_groups(s.prefilter_side(), probes)),
            (BAKE[6], map_groups(tile, probes)),
        ]);
    }
    all
}

/// A thread a block of the fast path's irradiance.
pub(super) fn block_image((width, height): (u32, u32), block: u32) -> Workgroups {
    Workgroups::for_image(width.div_ceil(block), height.div_ceil(block), IMAGE_TILE)
}

/// The frame's dispatches, each with its label, in order.
fn frame_dispatches(s: &LightfieldSettings, size: (u32, u32)) -> Vec<(&'static str, Workgroups)> {
    let image = Workgroups::for_image(size.0, size.1, IMAGE_TILE);
    let glossy = s.shade.glossy;
    let mut all = Vec::new();
    match s.shade.algorithm {
        ShadingAlgorithm::Naive => all.push((TRACE, image)),
        ShadingAlgorithm::Filtered => {
            all.push((TRACE, image));
            let filters = if glossy { 4 } else { 2 };
            all.extend(std::iter::repeat_n((FILTER, image), filters));
            all.push((TEMPORAL, image));
        }
        ShadingAlgorithm::Prefiltered if glossy => {
            all.extend([(TRACE, image), (FILTER, image), (FILTER, image)]);
            all.push((TEMPORAL, image));
        }
        ShadingAlgorithm::Prefiltered => {}
    }
    if s.shade.algorithm == ShadingAlgorithm::Prefiltered && s.shade.irradiance_block > 1 {
        all.push((IRRADIANCE, block_image(size, s.shade.irradiance_block)));
    }
    all.push((RESOLVE, image));
    all
}

impl TechniqueKind for LightfieldKind {
    fn name(&self) -> &'static str {
        match self.algorithm {
            ShadingAlgorithm::Prefiltered => "lightfield",
            ShadingAlgorithm::Filtered => "lightfield-traced",
            ShadingAlgorithm::Naive => "lightfield-naive",
        }
    }
    fn description(&self) -> &'static str {
        match self.algorithm {
            ShadingAlgorithm::Prefiltered => {
                "light-field probes: prefiltered irradiance with visibility, a filtered glossy ray"
            }
            ShadingAlgorithm::Filtered => {
                "light-field probes: a Lambertian and a glossy ray a pixel, filtered"
            }
            ShadingAlgorithm::Naive => "light-field probes: Monte Carlo rays, unfiltered",
        }
    }
    fn check(&self, spec: &TechniqueSpec) -> Result<Vec<String>, RenderError> {
        let mut warnings = Vec::new();
        self.settings(spec, &mut warnings)?;
        Ok(warnings)
    }
    fn resolved_settings(&self, spec: &TechniqueSpec) -> Result<toml::Table, RenderError> {
        Ok(crate::settings::as_table(
            &self.settings(spec, &mut Vec::new())?,
        ))
    }
    fn setting_doc(&self, _spec: &TechniqueSpec, path: &[&str]) -> Option<&'static str> {
        <LightfieldSettings as crate::settings::SettingDocs>::setting_doc(path)
    }
    fn plan(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<Allocation>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        Ok(resources::plan(
            &grid_of(scene, &settings)?,
            &settings,
            size,
        ))
    }
    fn dispatches(
        &self,
        spec: &TechniqueSpec,
        scene: &Scene,
        size: (u32, u32),
    ) -> Result<Vec<(&'static str, Workgroups)>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        let mut all = bake_dispatches(&grid_of(scene, &settings)?, &settings);
        all.extend(frame_dispatches(&settings, size));
        all.push((
            "lightfield/view",
            Workgroups::for_image(size.0, size.1, IMAGE_TILE),
        ));
        Ok(all)
    }
    fn build(
        &self,
        cx: &TechniqueContext,
        spec: &TechniqueSpec,
    ) -> Result<Box<dyn Technique>, RenderError> {
        let settings = self.settings(spec, &mut Vec::new())?;
        Ok(Box::new(Lightfield::new(cx, self.name(), &settings)?))
    }
}
