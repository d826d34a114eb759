//! The CPU reference shader: what a pixel's colour should be, in f64, with the formulas and
//! constants the emitted `shade`, `shadow`, `occlusion` and `fog` use (`lower/shading.rs`).

use crate::reference::eval;
use crate::scene::{LightKind, Occlusion, Scene, Shadow};
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

/// The unit direction from `p` towards `light` and how far a shadow ray goes: to a point
/// light, or `max_distance` for a directional one. (A light at the point itself lights it
/// from no direction: zero, not NaN.)
pub fn towards(scene: &Scene, light: &crate::scene::Light, p: DVec3) -> (DVec3, f64) {
    match light.kind {
        LightKind::Directional(d) => (d.normalize(), scene.trace.max_distance),
        LightKind::Point(pos) => (unit_or_zero(pos - p), (pos - p).length()),
    }
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
    let (base, specular) = if crate::reference::blend::has_blends(scene) {
        // Across a smooth operator's seam, two materials by its weight (`crate::reference::blend`).
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
        let (l, far) = towards(scene, light, p);
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
        let step = n * crate::reference::texture::normal_step(p, pattern.scale);
        unit_or_zero(eval::surface(scene, p + step).1 - q)
    } else {
        DVec3::ZERO
    };
    let w = crate::reference::texture::weight(&pattern, q, nq);
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
