//! Where rays make the field be evaluated: along the camera's rays, and from the surfaces they
//! hit along shadow rays to each light, occlusion's normals, reflected and refracted rays —
//! each point recorded in every annotated node's own coordinates with the kind of ray.

use super::Rng;
use crate::reference::{eval, pixel, shading};
use crate::scene::{NodeId, Scene, Shadow};
use crate::view::View;
use glam::DVec3;
use std::collections::HashMap;

/// What reaches a sampled point (a warning names it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ray {
    /// A camera ray.
    Camera,
    /// A shadow ray from a surface the camera sees towards a light.
    Shadow,
    /// Occlusion's samples along a seen surface's normal.
    Occlusion,
    /// A ray reflected off a seen mirror (and shadow rays from where it lands).
    Reflected,
    /// A ray refracted into a seen transparent solid and out of it.
    Refracted,
    /// No ray: a point of the annotated shape's own box (or of the search of its region).
    Region,
}

impl Ray {
    /// How a warning says it.
    pub fn say(self) -> &'static str {
        match self {
            Ray::Camera => "the camera's rays reach this point",
            Ray::Shadow => "only shadow rays towards a light may reach this point",
            Ray::Occlusion => "occlusion's samples along a surface's normal reach this point",
            Ray::Reflected => "rays reflected off a mirror reach this point",
            Ray::Refracted => "rays refracted through a transparent solid reach this point",
            Ray::Region => "the point lies in the annotated shape's region, sampled whole",
        }
    }
}

/// Points recorded per annotated node, with what reaches them.
pub type Seen = HashMap<NodeId, Vec<(DVec3, Ray)>>;

/// Most points recorded per annotated node (a node used through shared `let`s or many `repeat`
/// copies is evaluated many times per point).
const MAX_RECORDED: usize = 20_000;

/// Records where the whole scene's evaluation at world point `p` evaluates each annotated node.
struct Recorder<'a> {
    scene: &'a Scene,
    seen: Seen,
}

impl Recorder<'_> {
    fn record(&mut self, p: DVec3, ray: Ray) {
        let seen = &mut self.seen;
        eval::node_seen(self.scene, self.scene.root, p, &mut |id, q| {
            if let Some(v) = seen.get_mut(&id)
                && v.len() < MAX_RECORDED
            {
                v.push((q, ray));
            }
        });
    }

    /// `n` points along the ray from `o` in the unit direction `d` up to `far`: half spread
    /// evenly, half towards `o` over twelve octaves.
    fn along(&mut self, o: DVec3, d: DVec3, far: f64, n: usize, ray: Ray, rng: &mut Rng) {
        for i in 0..n {
            let u = rng.unit();
            let t = if i % 2 == 0 {
                u * far
            } else {
                far * (u * 12.0 - 12.0).exp2()
            };
            self.record(o + d * t, ray);
        }
    }
}

/// The points, in each annotated node's own coordinates, at which the scene's field is
/// evaluated along `world` camera rays (16:9, the default image shape) from the eye to
/// `max_distance`, and — when lights cast shadows, occlusion is on or materials reflect or
/// let light through — along the secondary rays from the surfaces `hits` more camera rays meet
/// (`per_ray` points on each).
pub fn where_rays_evaluate(
    scene: &Scene,
    annotated: &[NodeId],
    world: usize,
    (hits, per_ray): (usize, usize),
) -> Seen {
    let mut rec = Recorder {
        scene,
        seen: annotated.iter().map(|&id| (id, vec![])).collect(),
    };
    let view = View::new(&scene.camera, 1280, 720);
    let far = scene.trace.max_distance;
    let mut rng = Rng(0x5eed_1a55);
    for _ in 0..world / 2 {
        let rd = view.ray(rng.unit() * 1280.0, rng.unit() * 720.0);
        rec.along(view.eye, rd, far, 2, Ray::Camera, &mut rng);
    }
    let secondary =
        shading::has_shadows(scene) || pixel::has_paths(scene) || scene.occlusion.is_some();
    if secondary {
        // A hit threshold for finding surfaces: a thousandth of the distance to the target.
        let h = (view.eye - scene.camera.target).length().max(1e-6) * 1e-3;
        for _ in 0..hits {
            let rd = view.ray(rng.unit() * 1280.0, rng.unit() * 720.0);
            if let Some(t) = pixel::march(scene, view.eye, rd, 1.0, h, far) {
                from_surface(&mut rec, view.eye + rd * t, rd, (h, per_ray), &mut rng);
            }
        }
    }
    rec.seen
}

/// The secondary rays from the surface point `p` a ray along `rd` met: shadow rays, occlusion
/// and, off a mirror or through a transparent solid, the ray that goes on (one bounce, with
/// shadow rays where a reflected ray lands).
fn from_surface(rec: &mut Recorder, p: DVec3, rd: DVec3, (h, n): (f64, usize), rng: &mut Rng) {
    let scene = rec.scene;
    let far = scene.trace.max_distance;
    let facing = pixel::face_forward(eval::normal(scene, p, h), rd);
    shadows(rec, p, facing, (h, n), Ray::Shadow, rng);
    if let Some(o) = scene.occlusion {
        rec.along(p, facing, o.distance, n / 2 + 1, Ray::Occlusion, rng);
    }
    let m = eval::surface(scene, p).0;
    let Some(mat) = shading::material_of(scene, m).filter(|m| m.continues()) else {
        return;
    };
    let lift = shading::lift(scene, p, h);
    // (Both a mirror and a transparent surface reflect: the material continues.)
    let r = rd - 2.0 * rd.dot(facing) * facing;
    let o = p + facing * lift;
    rec.along(o, r, far, n, Ray::Reflected, rng);
    if let Some(t) = pixel::march(scene, o, r, 1.0, h, far) {
        let q = o + r * t;
        let nq = pixel::face_forward(eval::normal(scene, q, h), r);
        shadows(rec, q, nq, (h, n), Ray::Reflected, rng);
    }
    if mat.transparent > 0.0 {
        let into = pixel::refract(rd, facing, 1.0 / mat.ior);
        if into == DVec3::ZERO {
            return;
        }
        let o = p - facing * lift;
        // Inside the solid, to where it leaves (traced on −f), then on in the bent direction.
        let Some(t) = pixel::march(scene, o, into, -1.0, h, far) else {
            rec.along(o, into, far, n, Ray::Refracted, rng);
            return;
        };
        rec.along(o, into, t, n / 2 + 1, Ray::Refracted, rng);
        let q = o + into * t;
        let out_n = eval::normal(scene, q, h);
        let out_n = if into.dot(out_n) > 0.0 { out_n } else { -out_n };
        let out = pixel::refract(into, -out_n, mat.ior);
        let out = if out == DVec3::ZERO {
            into - 2.0 * into.dot(out_n) * out_n
        } else {
            out
        };
        let lift = shading::lift(scene, q, h);
        rec.along(q + out_n * lift, out, far, n, Ray::Refracted, rng);
    }
}

/// Shadow rays from the surface point `p` (normal `n` on the side the ray came from) towards
/// every light that casts shadows, as far as the light (or `max_distance`).
fn shadows(rec: &mut Recorder, p: DVec3, n: DVec3, (h, k): (f64, usize), ray: Ray, rng: &mut Rng) {
    let scene = rec.scene;
    let o = p + n * shading::lift(scene, p, h);
    for light in scene.lights.iter().filter(|l| l.shadow != Shadow::None) {
        let (l, far) = shading::towards(scene, light, o);
        if l != DVec3::ZERO && l.dot(n) > 0.0 {
            rec.along(o, l, far, k, ray, rng);
        }
    }
}
