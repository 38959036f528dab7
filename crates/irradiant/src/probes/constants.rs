//! Constants the probe techniques' Rust and WGSL share, defined once (the shader library serves
//! them as the module `probe_constants`).

irradiant_gpu::wgsl_constants! {
    /// Relocation (003 §5) moves a probe by less than this share of the spacing on each axis,
    /// so that it keeps its cell and the grid's indexing holds.
    RELOCATION_LIMIT: f32 = 0.45;
    /// How close to a surface a relocated probe may stand, as a share of the spacing; also how
    /// far past the grid's outer layers it may go (`relocation_keeps_grid`).
    RELOCATION_SURFACE_STEP: f32 = 0.05;
    /// A swallowed probe's exits tie (`relocation_exits_tie`) when a backface within this share
    /// of the closest one's distance lies more than 60° from it: the probe stands on a column's
    /// axis, or in a wall's very middle, and the ray set would pick its exit.
    RELOCATION_EXIT_TIE: f32 = 0.02;
    /// Relocation's first step moves a probe of the grid's outer layers this share of the
    /// spacing inwards. A volume's box fitted to a room's walls puts those layers in the
    /// walls' planes, where a ray from the probe misses the wall it starts in: the probe saw
    /// half the void behind a one-sided wall, or a solid wall's far side, and relocation could
    /// not tell. A hair inside, it sees the wall's face and steps off it (docs/ddgi.md, "A
    /// volume fitted to the walls").
    OUTER_PROBE_INSET: f32 = 1e-4;
}
