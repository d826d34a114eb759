//! The CPU reference shader: what a pixel's colour should be, in f64, with the formulas and
//! constants the emitted `shade`, `shadow`, `occlusion` and `fog` use (`lower/shading.rs`).

use crate::eval;
use crate::scene::{LightKind, Occlusion, Scene, Shadow, Trace};
use crate::trace::{self, Threshold};
use crate::view::View;
use glam::DVec3;

/// Ambient light term of `shade` (Munini §2.3: Lambert with an ambient term).
pub const AMBIENT: f64 = 0.12;

/// Base colour (sRGB) of surfaces without a material.
pub const DEFAULT_COLOR: DVec3 = DVec3::new(0.8, 0.8, 0.8);

/// Phong exponent of the specular term.
pub const SHININESS: f64 = 32.0;

/// Most steps of a shadow ray.
pub const SHADOW_STEPS: u32 = 64;

/// Whether some light casts shadows (then `shade` takes the hit threshold `h` and calls
/// `shadow`).
pub fn has_shadows(scene: &Scene) -> bool {
    scene.lights.iter().any(|l| l.shadow != Shadow::None)
}

/// How much of the light in direction `l` reaches the surface point `p` of normal `n`: sphere
/// tracing towards it from `p` moved along `n` by Keinert's ε_dynamic = 2·max(h, |f(p)|)
/// (§3.3), up to `far`; 0 once a step comes within `h` of a surface; with `k` > 0 the penumbra
/// min(k·f/t) of the closest approach (soft), else 1 (hard). At most [`SHADOW_STEPS`]
/// evaluations; a ray that runs out counts as lit.
pub fn shadow(scene: &Scene, p: DVec3, n: DVec3, l: DVec3, far: f64, h: f64, k: f64) -> f64 {
    let p = p + n * lift(scene, p, h);
    let (mut t, mut lit) = (0.0, 1.0f64);
    for _ in 0..SHADOW_STEPS {
        if t >= far {
            break;
        }
        let d = eval::distance(scene, p + l * t);
        if d < h {
            lit = 0.0;
            break;
        }
        if k > 0.0 {
            lit = lit.min(k * d / t.max(1e-6));
        }
        t += d;
    }
    lit.clamp(0.0, 1.0)
}

/// Ambient occlusion at `p` of normal `n` (Evans 2006, as Keinert et al. §1 cite it): the
/// clearance missing at `samples` points i·δ along the normal, weighted by 2⁻ⁱ and relative to
/// δ: clamp(1 − strength·Σ 2⁻ⁱ(iδ − f(p + iδ·n))/δ, 0, 1) — 1 in the open, less in creases.
pub fn occlusion(scene: &Scene, o: &Occlusion, p: DVec3, n: DVec3) -> f64 {
    let delta = o.distance / o.samples as f64;
    let mut missing = 0.0;
    let mut w = 0.5;
    for i in 1..=o.samples {
        let s = delta * i as f64;
        missing += w * (s - eval::distance(scene, p + n * s));
        w *= 0.5;
    }
    (1.0 - o.strength * missing / delta).clamp(0.0, 1.0)
}

/// The linear colour of the surface point `p` (normal `n`, seen along `rd`, material id
/// `material`: 0 the default, i + 1 the i-th declared) under the scene's lights: ambient and
/// Lambert (Munini §2.3) scaled by the occlusion, Blinn–Phong highlights, each shadowing
/// light's terms scaled by [`shadow`] (`h`: the hit threshold there).
pub fn shade(scene: &Scene, p: DVec3, n: DVec3, rd: DVec3, material: u32, h: f64) -> DVec3 {
    let spec_of = |m: u32| material_of(scene, m).map_or(0.0, |m| m.specular);
    let (base, specular) = if crate::blend::has_blends(scene) {
        // Across a smooth operator's seam, two materials by its weight (`crate::blend`).
        let bl = eval::blend(scene, p);
        let (a, b) = (albedo(scene, bl.a, p, n), albedo(scene, bl.b, p, n));
        (
            a * (1.0 - bl.t) + b * bl.t,
            spec_of(bl.a) * (1.0 - bl.t) + spec_of(bl.b) * bl.t,
        )
    } else {
        (albedo(scene, material, p, n), spec_of(material))
    };
    let ao = scene.occlusion.map_or(1.0, |o| occlusion(scene, &o, p, n));
    let mut color = base * AMBIENT * ao;
    for light in &scene.lights {
        let (l, far) = match light.kind {
            LightKind::Directional(d) => (d.normalize(), scene.trace.max_distance),
            // (A light at the point itself lights it from no direction: zero, not NaN.)
            LightKind::Point(pos) => (unit_or_zero(pos - p), (pos - p).length()),
        };
        let diffuse = n.dot(l).max(0.0);
        let mut lc = crate::color::linear(light.color) * light.intensity;
        match light.shadow {
            Shadow::None => {}
            Shadow::Hard => lc *= shadow(scene, p, n, l, far, h, 0.0),
            Shadow::Soft(k) => lc *= shadow(scene, p, n, l, far, h, k),
        }
        color += base * lc * diffuse * ao;
        if specular > 0.0 {
            // (A light straight along the ray has no half vector: no highlight, not NaN.)
            let half = unit_or_zero(l - rd);
            color += lc * n.dot(half).max(0.0).powf(SHININESS) * specular;
        }
    }
    color
}

/// The linear base colour of material `m` at the surface point `p` of normal `n`: its colour,
/// or with a pattern (Liktor §4) mix(colour, second, w), w the pattern's weight at the point in
/// the own coordinates of the shape the material was given to (`eval::surface`), so that the
/// pattern follows the shape's transforms; a triplanar pattern's normal there is where a step
/// along `n` (`texture::normal_step`) goes.
pub fn albedo(scene: &Scene, m: u32, p: DVec3, n: DVec3) -> DVec3 {
    let Some(mat) = material_of(scene, m) else {
        return crate::color::linear(DEFAULT_COLOR);
    };
    let first = crate::color::linear(mat.color);
    let Some(pattern) = mat.pattern else {
        return first;
    };
    let q = eval::surface(scene, p).1;
    let nq = if pattern.kind == crate::scene::PatternKind::Tiles {
        let step = n * crate::texture::normal_step(p, pattern.scale);
        unit_or_zero(eval::surface(scene, p + step).1 - q)
    } else {
        DVec3::ZERO
    };
    let w = crate::texture::weight(&pattern, q, nq);
    // (As WGSL's mix: a·(1 − w) + b·w.)
    first * (1.0 - w) + crate::color::linear(pattern.other) * w
}

/// Material id `m` (0 the default, i + 1 the i-th declared), if declared.
pub fn material_of(scene: &Scene, m: u32) -> Option<&crate::scene::Material> {
    m.checked_sub(1).map(|i| &scene.materials[i as usize])
}

/// `v` normalised, or zero for the zero vector (as the shader's
/// `select(normalize(v), vec3(0), dot(v, v) == 0)`).
pub fn unit_or_zero(v: DVec3) -> DVec3 {
    if v.dot(v) == 0.0 {
        DVec3::ZERO
    } else {
        v.normalize()
    }
}

/// How far a secondary ray's origin moves off the surface point `p`: Keinert's
/// ε_dynamic = 2·max(h, |f(p)|) (§3.3).
pub fn lift(scene: &Scene, p: DVec3, h: f64) -> f64 {
    2.0 * eval::distance(scene, p).abs().max(h)
}

/// `c` seen through the scene's fog (if any) from distance `t`:
/// mix(fog, c, e^(−density·t)), the fog's colour linear.
pub fn fog(scene: &Scene, c: DVec3, t: f64) -> DVec3 {
    match scene.fog {
        Some(f) => {
            let keep = (-f.density * t).exp();
            crate::color::linear(f.color).lerp(c, keep)
        }
        None => c,
    }
}

/// Most reflections off mirrors along one pixel's path (Keinert §5: two reflective bounces).
pub const REFLECTIONS: u32 = 2;

/// Most refractions along one pixel's path, internal reflections in a solid included (Keinert
/// §5: eight refractive bounces).
pub const REFRACTIONS: u32 = 8;

/// Most steps of a reflected or refracted ray.
pub const SECONDARY_STEPS: u32 = 128;

/// A path's weight below which it stops (its rest is the background).
pub const MIN_WEIGHT: f64 = 1.0 / 512.0;

/// Whether some material reflects or lets light through (then the entries follow rays on from
/// its surfaces: `path`).
pub fn has_paths(scene: &Scene) -> bool {
    scene.materials.iter().any(|m| m.continues())
}

/// Basic sphere tracing of `sign`·f (−1: inside a solid) from `ro` along the unit `rd`: the t
/// where it comes within `h` of the surface, or `None` if it passes `far` or
/// [`SECONDARY_STEPS`] run out.
pub fn march(scene: &Scene, ro: DVec3, rd: DVec3, sign: f64, h: f64, far: f64) -> Option<f64> {
    let mut t = 0.0;
    for _ in 0..SECONDARY_STEPS {
        let d = sign * eval::distance(scene, ro + rd * t);
        if d < h {
            return Some(t);
        }
        t += d;
        if t >= far {
            return None;
        }
    }
    None
}

/// Schlick's approximation of the Fresnel reflectance at the cosine `c` of the angle on the
/// side of the rarer medium, for a solid of index `ior` in air.
pub fn schlick(c: f64, ior: f64) -> f64 {
    let f0 = ((ior - 1.0) / (ior + 1.0)).powi(2);
    f0 + (1.0 - f0) * (1.0 - c.clamp(0.0, 1.0)).powi(5)
}

/// The refracted direction of the unit `i` at a surface of unit normal `n` (facing `i`) for
/// the ratio of indices `eta`, or zero at total internal reflection (as WGSL's `refract`).
pub fn refract(i: DVec3, n: DVec3, eta: f64) -> DVec3 {
    let c = n.dot(i);
    let k = 1.0 - eta * eta * (1.0 - c * c);
    if k < 0.0 {
        DVec3::ZERO
    } else {
        eta * i - (eta * c + k.sqrt()) * n
    }
}

/// The colour of a camera ray's hit where materials reflect or let light through, following
/// one path of reflected and refracted rays (Keinert §3.3, Fig. 13's jewel) without recursion.
/// At a hit seen from outside, material (R, T, ior, colour): the surface's own shading
/// `local` counts 1 − R − T; the reflected lobe weighs R + T·F, the refracted one T·(1 − F)
/// tinted by the colour (F: Schlick). Inside a solid the lobes are leaving (1 − F) and
/// internal reflection (F, all at total internal reflection). The path follows the heavier
/// lobe; the other one, a path that runs out of its bounces ([`REFLECTIONS`] off mirrors,
/// [`REFRACTIONS`] through solids) or falls below [`MIN_WEIGHT`], and a ray that escapes
/// take the background's colour. Each new ray starts from p moved along the normal to the
/// side it travels to by Keinert's ε_dynamic = 2·max(h, |f(p)|) (§3.3), and is traced by
/// [`march`] on f outside and −f inside a solid, with the camera ray's hit threshold `h`.
pub fn path(scene: &Scene, p: DVec3, n: DVec3, rd: DVec3, m: u32, h: f64, local: DVec3) -> DVec3 {
    path_counted(scene, p, n, rd, m, h, local).0
}

/// What a [`path`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bounces {
    /// Reflections off mirrors (and off transparent surfaces from outside).
    pub reflections: u32,
    /// Refractions into and out of solids, and reflections inside them.
    pub refractions: u32,
    /// Of those, total internal reflections.
    pub total_internal: u32,
}

/// [`path`], and what it did.
pub fn path_counted(
    scene: &Scene,
    mut p: DVec3,
    mut n: DVec3,
    mut rd: DVec3,
    mut m: u32,
    h: f64,
    mut local: DVec3,
) -> (DVec3, Bounces) {
    let mut count = Bounces::default();
    let bg = crate::color::linear(scene.background);
    let far = scene.trace.max_distance;
    let (mut acc, mut w) = (DVec3::ZERO, DVec3::ONE);
    let (mut inside, mut solid_ior) = (false, 1.0);
    loop {
        // The surface seen from outside: its own shading's share, and what goes on.
        let (r, t, ior, tint) = surface_of(scene, m, inside);
        if !inside {
            acc += w * (1.0 - r - t) * local;
            if r + t == 0.0 {
                return (acc, count);
            }
            solid_ior = ior;
        }
        // No normal (a zero gradient): nowhere to reflect or refract to.
        if n == DVec3::ZERO {
            let rest = if inside { 1.0 } else { r + t };
            return (acc + w * rest * bg, count);
        }
        // The normal on the ray's side (`faceForward`), so that a silhouette's normal facing
        // away from the ray does not send a reflection into the solid.
        let facing = if rd.dot(n) < 0.0 { n } else { -n };
        let (reflected, refracted, dir_t) = if inside {
            lobes_inside(rd, facing, solid_ior)
        } else {
            lobes_outside(rd, facing, r, t, ior, tint)
        };
        let mean = refracted.element_sum() / 3.0;
        let through = mean >= reflected && mean > 0.0;
        if !spend(&mut count, through, inside) {
            return (acc + w * (refracted + DVec3::splat(reflected)) * bg, count);
        }
        let dir = if through {
            acc += w * reflected * bg;
            w *= refracted;
            dir_t
        } else {
            if inside && dir_t == DVec3::ZERO {
                count.total_internal += 1;
            }
            acc += w * refracted * bg;
            w *= reflected;
            rd - 2.0 * rd.dot(facing) * facing
        };
        if w.max_element() < MIN_WEIGHT {
            return (acc + w * bg, count);
        }
        // A reflection stays on the ray's side of the surface, a refraction crosses it.
        let side = if through { -1.0 } else { 1.0 };
        let ro = p + facing * (side * lift(scene, p, h));
        if through {
            inside = !inside;
        }
        let sign = if inside { -1.0 } else { 1.0 };
        let Some(t) = march(scene, ro, dir, sign, h, far) else {
            return (acc + w * bg, count);
        };
        p = ro + dir * t;
        n = eval::normal(scene, p, h);
        rd = dir;
        if !inside {
            m = eval::sample(scene, p).mat.map_or(0, |i| i + 1);
            local = shade(scene, p, n, rd, m, h);
        }
    }
}

/// The reflectance, transmittance, index and linear tint of the surface of material `m` seen
/// from outside; nothing (no lobes) from inside a solid or for the default material.
fn surface_of(scene: &Scene, m: u32, inside: bool) -> (f64, f64, f64, DVec3) {
    match material_of(scene, m).filter(|_| !inside) {
        Some(mat) => (
            mat.reflect,
            mat.transparent,
            mat.ior,
            crate::color::linear(mat.color),
        ),
        None => (0.0, 0.0, 1.0, DVec3::ONE),
    }
}

/// Inside a solid of index `solid_ior`: the internal reflection's weight F (1 at total
/// internal reflection), the leaving lobe's 1 − F, and the leaving direction (zero at total
/// internal reflection).
fn lobes_inside(rd: DVec3, facing: DVec3, solid_ior: f64) -> (f64, DVec3, DVec3) {
    let dir_t = refract(rd, facing, solid_ior);
    let f = if dir_t == DVec3::ZERO {
        1.0
    } else {
        schlick(-dir_t.dot(facing), solid_ior)
    };
    (f, DVec3::splat(1.0 - f), dir_t)
}

/// At a surface seen from outside (reflectance `r`, transmittance `t`, index `ior`): the
/// reflected lobe's weight R + T·F, the refracted one's T·(1 − F) tinted, and the refracted
/// direction.
fn lobes_outside(
    rd: DVec3,
    facing: DVec3,
    r: f64,
    t: f64,
    ior: f64,
    tint: DVec3,
) -> (f64, DVec3, DVec3) {
    let dir_t = refract(rd, facing, 1.0 / ior);
    let f = if t > 0.0 {
        schlick(-rd.dot(facing), ior)
    } else {
        0.0
    };
    let refracted = if dir_t == DVec3::ZERO {
        DVec3::ZERO
    } else {
        t * (1.0 - f) * tint
    };
    (r + t * f, refracted, dir_t)
}

/// Spends one bounce of the path's budget: a way through or within a solid spends a
/// refraction, a mirror a reflection; `false` when that budget has run out.
fn spend(count: &mut Bounces, through: bool, inside: bool) -> bool {
    let budget = if through || inside {
        &mut count.refractions
    } else {
        &mut count.reflections
    };
    let limit = if through || inside {
        REFRACTIONS
    } else {
        REFLECTIONS
    };
    if *budget >= limit {
        return false;
    }
    *budget += 1;
    true
}

/// The linear colour of image point (x, y) of `view` (pixel centres at +0.5), as the compute
/// entry computes it before sRGB encoding: the ray traced by `trace`, the hit shaded with the
/// f64 normal over the tetrahedron at the hit threshold, followed through mirrors and solids
/// ([`path`]), fogged; a miss the background; with cone anti-aliasing the near miss blended
/// over it with its coverage (Munini §2.4).
pub fn pixel(scene: &Scene, trace: &Trace, view: &View, x: f64, y: f64) -> DVec3 {
    pixel_counted(scene, trace, view, x, y).0
}

/// [`pixel`], and the bounces of its paths.
pub fn pixel_counted(
    scene: &Scene,
    trace: &Trace,
    view: &View,
    x: f64,
    y: f64,
) -> (DVec3, Bounces) {
    let rd = view.ray(x, y);
    let r = trace::ray(scene, trace, view.eye, rd, view.pixel);
    let threshold = Threshold::new(scene, trace, view.pixel);
    let mut count = Bounces::default();
    let mut surface = |t: f64| {
        let p = view.eye + rd * t;
        let h = threshold.at(t);
        let n = eval::normal(scene, p, h);
        let m = eval::sample(scene, p).mat.map_or(0, |i| i + 1);
        let mut c = shade(scene, p, n, rd, m, h);
        if has_paths(scene) {
            let (through, did) = path_counted(scene, p, n, rd, m, h, c);
            c = through;
            count.reflections += did.reflections;
            count.refractions += did.refractions;
            count.total_internal += did.total_internal;
        }
        fog(scene, c, t)
    };
    let mut color = crate::color::linear(scene.background);
    if r.hit {
        color = surface(r.t);
    }
    if trace.antialias && r.cover > 0.0 {
        color = color.lerp(surface(r.cover_t), r.cover);
    }
    (color, count)
}
