//! A pixel's colour in f64: the camera ray traced, its hit shaded (`shading.rs`) and followed
//! through mirrors and solids along one path of reflected and refracted rays (Keinert §5, the
//! reference `lower/bounce.rs` mirrors step for step), fogged.

use super::eval;
use super::shading::{fog, lift, material_of, shade};
use crate::reference::trace::{self, Threshold};
use crate::scene::{Scene, Trace};
use crate::view::View;
use glam::DVec3;

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

/// The normal `n` turned to face the ray along `rd` (`faceForward`): `n` where the ray meets
/// it head on, else −n.
pub fn face_forward(n: DVec3, rd: DVec3) -> DVec3 {
    if rd.dot(n) < 0.0 { n } else { -n }
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
        // The normal on the ray's side, so that a silhouette's normal facing away from the ray
        // does not send a reflection into the solid.
        let facing = face_forward(n, rd);
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
