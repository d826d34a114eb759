//! The scene's lights, occlusion, fog and tracer settings, as the checker resolved them.

use glam::DVec3;

/// Smallest hit threshold, relative to the camera's distance from its target: keeps ε above the
/// f32 resolution of positions there (about 6e-8 of their magnitude).
pub const EPSILON_FLOOR: f64 = 1e-5;

/// A light.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Directional (towards the light) or positional.
    pub kind: LightKind,
    /// Colour (0..1).
    pub color: DVec3,
    /// Intensity multiplier.
    pub intensity: f64,
    /// Whether surfaces shade each other from it.
    pub shadow: Shadow,
    /// Settings computed from parameters (indexed as `check::LIGHT_KINDS`' parameters: the
    /// direction or position, `color`, `intensity`), as expressions per component; empty
    /// when none is.
    pub sym: crate::catalog::ArgSyms,
}

/// Ambient occlusion (Evans 2006, cited by Keinert et al. §1): `samples` evaluations of the
/// field along the normal at i·δ, δ = `distance`/`samples`, each missing clearance
/// iδ − f(p + iδ·n) weighted by 2⁻ⁱ; the ambient and diffuse light are scaled by
/// clamp(1 − strength·Σ 2⁻ⁱ(iδ − f)/δ, 0, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Occlusion {
    /// Evaluations along the normal.
    pub samples: u32,
    /// How far from the surface the last sample lies.
    pub distance: f64,
    /// How strongly missing clearance darkens.
    pub strength: f64,
}

/// Exponential distance fog: a hit at distance t along the ray keeps e^(−density·t) of its
/// colour and takes the rest from the fog's colour (misses keep the background).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// sRGB colour (0..1) of the fog.
    pub color: DVec3,
    /// Extinction per unit of distance.
    pub density: f64,
}

/// A light's shadow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shadow {
    /// None: every surface facing the light is lit.
    None,
    /// A shadow ray towards the light: lit or not.
    Hard,
    /// The penumbra estimate min(k·f/t) along the shadow ray, k the softness.
    Soft(f64),
}

/// Where light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Unit direction towards the light.
    Directional(DVec3),
    /// Position of a point light.
    Point(DVec3),
}

/// Which sphere-tracing variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Hart; Bálint Alg. 1.
    Basic,
    /// Keinert §3.1, Listing 2.
    Relaxed,
    /// Bálint Alg. 3.
    Enhanced,
    /// Liktor §5.4.
    Hybrid,
    /// Bán & Valasek 2023.
    Auto,
}

/// When a ray counts as having hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Epsilon {
    /// f < ε.
    Absolute(f64),
    /// f < t·(pixel footprint) (Bálint Eq. 2).
    Pixel,
}

/// Tracer settings: the variant and every parameter (each variant reads its own; the table
/// `check::TRACE_METHODS` says which a variant accepts and their defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trace {
    /// Variant.
    pub method: Method,
    /// Step budget: evaluations of the field the search may spend.
    pub steps: u32,
    /// Hit condition.
    pub epsilon: Epsilon,
    /// Rays stop beyond this distance.
    pub max_distance: f64,
    /// Relaxation ω: the over-relaxation factor (relaxed, ω ∈ [1, 2)) or the scale of the
    /// inferred planar step (enhanced, Bálint Alg. 3).
    pub omega: f64,
    /// Weight β of the slope's moving average (auto).
    pub beta: f64,
    /// Linear-search step below the distance bound, in units of ε(t) (hybrid).
    pub linear: f64,
    /// Regula falsi iterations after a sign change (hybrid).
    pub refine: u32,
    /// Fixed-point iterations of discontinuity reduction after a hit (Keinert §3.4, Eq. 3).
    pub discontinuity: u32,
    /// Hart's cone anti-aliasing (Munini §2.4), `basic` only: near misses in front of the hit
    /// blend into the pixel with their coverage.
    pub antialias: bool,
    /// What `relaxed` does when two unbounding spheres stop overlapping: `false` (`fallback
    /// reset`, the default, Keinert Listing 2) takes the step back by ω·step and sets ω = 1 for
    /// the rest of the ray; `true` (`fallback keep`, Bálint & Valasek Alg. 2) goes back to the
    /// last safe point plus its radius and keeps ω.
    pub keep_relaxation: bool,
}
