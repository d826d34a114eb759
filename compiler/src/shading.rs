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
    let lift = 2.0 * eval::distance(scene, p).abs().max(h);
    let p = p + n * lift;
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
    let (base, specular) = match material.checked_sub(1) {
        Some(i) => {
            let m = &scene.materials[i as usize];
            (m.color, m.specular)
        }
        None => (DEFAULT_COLOR, 0.0),
    };
    let base = crate::color::linear(base);
    let ao = scene.occlusion.map_or(1.0, |o| occlusion(scene, &o, p, n));
    let mut color = base * AMBIENT * ao;
    for light in &scene.lights {
        let (l, far) = match light.kind {
            LightKind::Directional(d) => (d.normalize(), scene.trace.max_distance),
            LightKind::Point(pos) => ((pos - p).normalize(), (pos - p).length()),
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
            let half = (l - rd).normalize();
            color += lc * n.dot(half).max(0.0).powf(SHININESS) * specular;
        }
    }
    color
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

/// The linear colour of image point (x, y) of `view` (pixel centres at +0.5), as the compute
/// entry computes it before sRGB encoding: the ray traced by `trace`, the hit shaded with the
/// f64 normal over the tetrahedron at the hit threshold, fogged; a miss the background; with
/// cone anti-aliasing the near miss blended over it with its coverage (Munini §2.4).
pub fn pixel(scene: &Scene, trace: &Trace, view: &View, x: f64, y: f64) -> DVec3 {
    let rd = view.ray(x, y);
    let r = trace::ray(scene, trace, view.eye, rd, view.pixel);
    let threshold = Threshold::new(scene, trace, view.pixel);
    let surface = |t: f64| {
        let p = view.eye + rd * t;
        let h = threshold.at(t);
        let n = eval::normal(scene, p, h);
        let m = eval::sample(scene, p).mat.map_or(0, |i| i + 1);
        fog(scene, shade(scene, p, n, rd, m, h), t)
    };
    let mut color = crate::color::linear(scene.background);
    if r.hit {
        color = surface(r.t);
    }
    if trace.antialias && r.cover > 0.0 {
        color = color.lerp(surface(r.cover_t), r.cover);
    }
    color
}
