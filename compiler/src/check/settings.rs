//! Checking the settings statements: camera, tracer, bound and background (lights, materials,
//! occlusion and fog in `look.rs`), each a table of parameters bound by the same code as call
//! arguments.

use super::Checker;
use crate::catalog::{Param, Ty, Val, opt, req};
use crate::diag::{Diagnostic, Span};
use crate::scene::{
    BoundShape, Camera, Convex, Fog, Light, LightKind, Material, Method, Node, NodeId, Occlusion,
    Scene, Shadow, Trace,
};
use crate::syntax::{Arg, Expr, Ident, Setting};
use glam::DVec3;

pub(super) const fn v(x: f64, y: f64, z: f64) -> Val {
    Val::Vec3(DVec3::new(x, y, z))
}

const CAMERA: &[Param] = &[
    opt("eye", Ty::Vec3, v(0.0, 1.0, -5.0)),
    opt("target", Ty::Vec3, v(0.0, 0.0, 0.0)),
    opt("up", Ty::Axis, v(0.0, 1.0, 0.0)),
    opt("fov", Ty::Angle, Val::Num(std::f64::consts::PI / 4.0)),
];

const CONVEX: Param = opt("convex", Ty::Word(&["no", "yes"]), Val::Word(0));

/// Bound kinds (`bound sphere { .. }`, Keinert §3.5); the first is the default. `auto` is the
/// bounding sphere the catalog's rules give the scene; `convex yes` declares the enclosed
/// object convex, so rays starting inside it are traced backwards from the bound's far side.
pub const BOUND_KINDS: &[(&str, &[Param])] = &[
    ("auto", &[CONVEX]),
    (
        "sphere",
        &[
            opt("center", Ty::Vec3, v(0.0, 0.0, 0.0)),
            req("radius", Ty::Positive),
            CONVEX,
        ],
    ),
    (
        "box",
        &[
            opt("center", Ty::Vec3, v(0.0, 0.0, 0.0)),
            req("size", Ty::Size),
            CONVEX,
        ],
    ),
];

pub(super) use crate::syntax::BLOCK_KEYWORDS;

/// The background without a `background` statement (sRGB).
const DEFAULT_BACKGROUND: DVec3 = DVec3::new(0.08, 0.09, 0.12);

/// Relative spacing of f32 numbers (2⁻²³).
pub(super) const F32_RESOLUTION: f64 = 1.0 / 8_388_608.0;

/// Settings collected while checking, with where each was first given.
#[derive(Default)]
pub(super) struct Settings {
    pub(super) camera: Option<(Camera, Span)>,
    pub(super) lights: Vec<Light>,
    pub(super) trace: Option<(Trace, Span)>,
    background: Option<(DVec3, Span)>,
    pub(super) occlusion: Option<(Occlusion, Span)>,
    /// The fog, its colour `None` for the background's.
    pub(super) fog: Option<((Option<DVec3>, f64), Span)>,
    /// The declared bound; `None` inside for `bound auto`, resolved once the root is known.
    pub(super) bound: Option<((Option<Convex>, bool), Span)>,
}

impl Settings {
    /// The declared camera, or the default one.
    pub(super) fn camera(&self) -> Camera {
        self.camera.map(|c| c.0).unwrap_or(Camera {
            eye: DVec3::new(0.0, 1.0, -5.0),
            target: DVec3::ZERO,
            up: DVec3::Y,
            fov: std::f64::consts::PI / 4.0,
        })
    }

    pub(super) fn finish(self, nodes: Vec<Node>, root: NodeId, materials: Vec<Material>) -> Scene {
        let bound = self.bound.map(|((declared, convex), _)| {
            declared.unwrap_or_else(|| Convex {
                shape: BoundShape::Sphere {
                    center: nodes[root].bound.center,
                    radius: nodes[root].bound.radius,
                },
                convex,
            })
        });
        let camera = self.camera();
        let background = self.background.map_or(DEFAULT_BACKGROUND, |b| b.0);
        let lights = if self.lights.is_empty() {
            vec![Light {
                kind: LightKind::Directional(DVec3::new(-0.4, 1.0, -0.3).normalize()),
                color: DVec3::ONE,
                intensity: 1.0,
                shadow: Shadow::None,
                sym: Vec::new(),
            }]
        } else {
            self.lights
        };
        Scene {
            nodes,
            root,
            materials,
            camera,
            lights,
            background,
            trace: self
                .trace
                .map_or_else(super::tracer::default_trace, |t| t.0),
            bound,
            occlusion: self.occlusion.map(|o| o.0),
            fog: self.fog.map(|((color, density), _)| Fog {
                color: color.unwrap_or(background),
                density,
            }),
            params: Vec::new(),
        }
    }
}

impl Checker<'_> {
    /// `camera {..}`, `light kind {..}`, `trace method {..}`, `material name {..}`.
    pub(super) fn block(
        &mut self,
        keyword: &Ident,
        kind: Option<&Ident>,
        settings: &[Setting],
        span: Span,
    ) {
        let args: Vec<Arg> = settings
            .iter()
            .map(|s| Arg {
                name: Some(s.key.clone()),
                value: s.value.clone(),
            })
            .collect();
        match keyword.name.as_str() {
            "camera" => self.camera(keyword, kind, settings, &args, span),
            "light" => self.light(kind, &args, span),
            "occlusion" => self.occlusion(keyword, kind, &args, span),
            "fog" => self.fog(keyword, kind, &args, span),
            "trace" => self.trace(kind, &args, span),
            "bound" => self.bound(kind, &args, span),
            _ => self.material(kind, &args, span),
        }
    }

    /// `camera { eye  target  up  fov }`: the field of view within range, a view direction,
    /// and an `up` off it.
    fn camera(
        &mut self,
        keyword: &Ident,
        kind: Option<&Ident>,
        settings: &[Setting],
        args: &[Arg],
        span: Span,
    ) {
        self.no_kind(keyword, kind);
        let Some(a) = self.bind("camera", CAMERA, args, span) else {
            return;
        };
        let camera = Camera {
            eye: a[0].vec(),
            target: a[1].vec(),
            up: a[2].vec(),
            fov: a[3].num(),
        };
        if !(0.01..=3.1).contains(&camera.fov) {
            self.diags.push(
                Diagnostic::error(
                    setting_span(settings, "fov", span),
                    "the field of view must be between 0.6deg and 177deg",
                )
                .label("out of range"),
            );
        } else if (camera.eye - camera.target).length()
            <= F32_RESOLUTION * camera.eye.length().max(camera.target.length())
        {
            self.diags.push(
                Diagnostic::error(span, "the camera's eye and target coincide")
                    .label("no view direction"),
            );
        } else if (camera.eye - camera.target)
            .normalize()
            .cross(camera.up)
            .length()
            < 1e-6
        {
            self.diags.push(
                Diagnostic::error(span, "the camera looks along its `up` direction")
                    .label("choose another `up`"),
            );
        }
        self.once(|s| &mut s.camera, camera, span, "camera");
    }

    /// `trace method { .. }`: the tracer and its settings.
    fn trace(&mut self, kind: Option<&Ident>, args: &[Arg], span: Span) {
        let methods = super::tracer::TRACE_METHODS
            .iter()
            .map(|(n, _, p)| (*n, *p));
        let Some((name, params)) = self.kind_of(methods, kind, "trace") else {
            return;
        };
        let method = super::tracer::TRACE_METHODS
            .iter()
            .find(|m| m.0 == name)
            .map(|m| m.1)
            .unwrap_or(Method::Basic);
        let Some(a) = self.bind(&format!("trace {name}"), params, args, span) else {
            return;
        };
        let trace = super::tracer::build(method, |n| {
            params.iter().position(|p| p.name == n).map(|i| a[i])
        });
        self.once(|s| &mut s.trace, trace, span, "trace");
    }

    /// `bound sphere { center (0, 1, 0) radius 2 }`, `bound box { size 4 }`, `bound auto {}`.
    fn bound(&mut self, kind: Option<&Ident>, args: &[Arg], span: Span) {
        let kinds = BOUND_KINDS.iter().map(|(n, p)| (*n, *p));
        let Some((name, params)) = self.kind_of(kinds, kind, "bound") else {
            return;
        };
        let Some(a) = self.bind(&format!("bound {name}"), params, args, span) else {
            return;
        };
        let convex = matches!(a[a.len() - 1], Val::Word(1));
        let shape = match name {
            "sphere" => Some(BoundShape::Sphere {
                center: a[0].vec(),
                radius: a[1].num(),
            }),
            "box" => {
                let size = a[1].vec();
                if size.min_element() <= 0.0 {
                    self.diags.push(
                        Diagnostic::error(
                            setting_span_of(args, "size", span),
                            "a bounding box needs every edge longer than 0",
                        )
                        .label("an edge of length 0 encloses nothing"),
                    );
                    return;
                }
                Some(BoundShape::Box {
                    center: a[0].vec(),
                    half: size / 2.0,
                })
            }
            _ => None,
        };
        let declared = shape.map(|shape| Convex { shape, convex });
        self.once(|s| &mut s.bound, (declared, convex), span, "bound");
    }

    /// `background #202030`
    pub(super) fn value_statement(&mut self, keyword: &Ident, value: &Expr) {
        if let Some(Val::Vec3(c)) = self.convert(value, Ty::Color, "background") {
            self.once(
                |s| &mut s.background,
                c,
                keyword.span.to(value.span),
                "background",
            );
        }
    }

    /// Resolves the name after `light` or `trace` (default: the table's first entry).
    pub(super) fn kind_of(
        &mut self,
        table: impl Iterator<Item = (&'static str, &'static [Param])> + Clone,
        kind: Option<&Ident>,
        what: &str,
    ) -> Option<(&'static str, &'static [Param])> {
        let Some(kind) = kind else {
            return table.clone().next();
        };
        if let Some(found) = table.clone().find(|(n, _)| *n == kind.name) {
            return Some(found);
        }
        let names: Vec<&str> = table.map(|(n, _)| n).collect();
        let mut d = Diagnostic::error(kind.span, format!("unknown {what} kind `{}`", kind.name))
            .label("not known");
        d = match self.did_you_mean(&kind.name, names.iter().copied()) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.note(format!("the kinds are: {}", names.join(", "))),
        };
        self.diags.push(d);
        None
    }

    /// Reports a name after a block keyword that takes none (`camera`, `occlusion`, `fog`).
    pub(super) fn no_kind(&mut self, keyword: &Ident, kind: Option<&Ident>) {
        if let Some(k) = kind {
            self.diags.push(
                Diagnostic::error(k.span, format!("`{}` has no kind", keyword.name))
                    .label("remove this name"),
            );
        }
    }

    /// Stores a setting that may be given only once.
    pub(super) fn once<T>(
        &mut self,
        slot: impl Fn(&mut Settings) -> &mut Option<(T, Span)>,
        value: T,
        span: Span,
        what: &str,
    ) {
        match slot(&mut self.settings) {
            Some((_, first)) => {
                let first = *first;
                self.diags.push(
                    Diagnostic::error(span, format!("`{what}` is given twice"))
                        .label("second")
                        .also(first, "first"),
                );
            }
            s @ None => *s = Some((value, span)),
        }
    }
}

fn setting_span_of(args: &[Arg], key: &str, default: Span) -> Span {
    args.iter()
        .find(|a| a.name.as_ref().is_some_and(|n| n.name == key))
        .map_or(default, |a| {
            a.name
                .as_ref()
                .map_or(a.value.span, |n| n.span)
                .to(a.value.span)
        })
}

fn setting_span(settings: &[Setting], key: &str, default: Span) -> Span {
    settings
        .iter()
        .find(|s| s.key.name == key)
        .map_or(default, |s| s.key.span.to(s.value.span))
}
