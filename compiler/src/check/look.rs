//! Checking what a scene looks like: lights with their shadows, materials, ambient occlusion and
//! fog, each a table of parameters bound by the same code as call arguments.

use super::Checker;
use super::args::RunTime;
use super::settings::v;
use crate::catalog::{Param, Ty, Val, opt, req};
use crate::diag::{Diagnostic, Span};
use crate::reference::texture::{MAX_OCTAVES, PATTERNS};
use crate::scene::{Light, LightKind, Material, Occlusion, Pattern, Shadow};
use crate::syntax::{Arg, Ident};

/// `material name { color  specular  reflect  transparent  ior }`.
const MATERIAL: &[Param] = &[
    opt("color", Ty::Color, v(0.8, 0.8, 0.8)),
    opt("specular", Ty::Fraction, Val::Num(0.0)),
    opt("reflect", Ty::Fraction, Val::Num(0.0)),
    opt("transparent", Ty::Fraction, Val::Num(0.0)),
    opt("ior", Ty::Range(1.0, 5.0), Val::Num(1.5)),
];

/// A light's shadow: none, hard (Munini §2.3, Liktor: a shadow ray towards the light), or soft
/// (the penumbra from the shadow ray's closest approach, sharper with a larger `softness`).
const SHADOW: Param = opt("shadow", Ty::Word(&["none", "hard", "soft"]), Val::Word(0));
const SOFTNESS: Param = opt("softness", Ty::Positive, Val::Num(8.0));

/// Light kinds (`light point { .. }`); the first is the default.
pub const LIGHT_KINDS: &[(&str, &[Param])] = &[
    (
        "directional",
        &[
            opt("direction", Ty::Axis, v(-0.4, 1.0, -0.3)),
            opt("color", Ty::Color, v(1.0, 1.0, 1.0)),
            opt("intensity", Ty::Length, Val::Num(1.0)),
            SHADOW,
            SOFTNESS,
        ],
    ),
    (
        "point",
        &[
            req("position", Ty::Vec3),
            opt("color", Ty::Color, v(1.0, 1.0, 1.0)),
            opt("intensity", Ty::Length, Val::Num(1.0)),
            SHADOW,
            SOFTNESS,
        ],
    ),
];

/// A pattern's arguments: `checker(first, second, scale = 1, octaves = 4)`.
pub const PATTERN: &[Param] = &[
    req("first", Ty::Color),
    req("second", Ty::Color),
    opt("scale", Ty::Positive, Val::Num(1.0)),
    opt("octaves", Ty::CountTo(MAX_OCTAVES), Val::Num(4.0)),
];

/// Most samples of ambient occlusion (each is an evaluation of the field per shaded pixel).
pub const MAX_OCCLUSION_SAMPLES: u32 = 16;

/// `occlusion { samples 5  distance 0.5  strength 1 }` ([`Occlusion`]).
pub const OCCLUSION: &[Param] = &[
    opt("samples", Ty::CountTo(MAX_OCCLUSION_SAMPLES), Val::Num(5.0)),
    opt("distance", Ty::Positive, Val::Num(0.5)),
    opt("strength", Ty::Length, Val::Num(1.0)),
];

/// `fog { density 0.05  color #aabbcc }`: without a colour, the scene's background (the word
/// default stands for it).
pub const FOG: &[Param] = &[
    req("density", Ty::Positive),
    opt("color", Ty::Color, Val::Word(0)),
];

impl Checker<'_> {
    /// `light [directional|point] { .. }`.
    pub(super) fn light(&mut self, kind: Option<&Ident>, args: &[Arg], span: Span) {
        let Some((name, params)) =
            self.kind_of(LIGHT_KINDS.iter().map(|(n, p)| (*n, *p)), kind, "light")
        else {
            return;
        };
        let run_time = RunTime::Only(&["direction", "position", "color", "intensity"]);
        let what = format!("light {name}");
        let Some((a, sym)) = self.bind_args(&what, params, args, span, run_time) else {
            return;
        };
        let place = a[0].vec();
        if self.settings.lights.len() == super::MAX_LIGHTS {
            self.diags.push(
                Diagnostic::error(span, "the scene has too many lights")
                    .label("one light more than the limit")
                    .note(format!("the limit is {} lights: each is a term of the shading the GPU driver compiles", super::MAX_LIGHTS)),
            );
        }
        self.settings.lights.push(Light {
            kind: if name == "point" {
                LightKind::Point(place)
            } else {
                LightKind::Directional(place)
            },
            color: a[1].vec(),
            intensity: a[2].num(),
            shadow: match a[3] {
                Val::Word(1) => Shadow::Hard,
                Val::Word(2) => Shadow::Soft(a[4].num()),
                _ => Shadow::None,
            },
            sym,
        });
    }

    /// `occlusion { .. }`.
    pub(super) fn occlusion(
        &mut self,
        keyword: &Ident,
        kind: Option<&Ident>,
        args: &[Arg],
        span: Span,
    ) {
        self.no_kind(keyword, kind);
        let Some(a) = self.bind("occlusion", OCCLUSION, args, span) else {
            return;
        };
        let occlusion = Occlusion {
            samples: a[0].num() as u32,
            distance: a[1].num(),
            strength: a[2].num(),
        };
        self.once(|s| &mut s.occlusion, occlusion, span, "occlusion");
    }

    /// `fog { .. }`.
    pub(super) fn fog(&mut self, keyword: &Ident, kind: Option<&Ident>, args: &[Arg], span: Span) {
        self.no_kind(keyword, kind);
        let Some(a) = self.bind("fog", FOG, args, span) else {
            return;
        };
        let color = match a[1] {
            Val::Vec3(c) => Some(c),
            _ => None,
        };
        self.once(|s| &mut s.fog, (color, a[0].num()), span, "fog");
    }

    /// `material name { .. }`.
    pub(super) fn material(&mut self, kind: Option<&Ident>, args: &[Arg], span: Span) {
        let Some(name) = kind else {
            self.diags.push(
                Diagnostic::error(span, "a material needs a name")
                    .label("e.g. `material gold { color #d4af37 }`"),
            );
            return;
        };
        // (A material is only ever named after `:`, so a math function's name, such as the
        // common `floor`, cannot be mistaken for it.)
        if let Some(d) = self.reserved_name(name)
            && crate::catalog::math_fn(&name.name).is_none()
        {
            self.diags.push(d);
            self.failed.insert(name.name.clone());
            return;
        }
        if let Some(first) = self.materials.iter().find(|m| m.name == name.name) {
            let first = first.span;
            self.diags.push(
                Diagnostic::error(
                    name.span,
                    format!("material `{}` is defined twice", name.name),
                )
                .label("second definition")
                .also(first, "first definition"),
            );
            return;
        }
        let mut args = args.to_vec();
        let Some(pattern) = self.color_pattern(&mut args) else {
            self.failed.insert(name.name.clone());
            return;
        };
        let what = format!("material {}", name.name);
        let run_time = RunTime::Only(&["color", "specular"]);
        let Some((a, sym)) = self.bind_args(&what, MATERIAL, &args, span, run_time) else {
            self.failed.insert(name.name.clone());
            return;
        };
        let (reflect, transparent) = (a[2].num(), a[3].num());
        self.material_limits(name, reflect, transparent, span);
        self.material_item
            .entry(name.name.clone())
            .or_insert(self.item);
        self.materials.push(Material {
            name: name.name.clone(),
            color: a[0].vec(),
            specular: a[1].num(),
            reflect,
            transparent,
            ior: a[4].num(),
            pattern,
            span: name.span,
            sym,
        });
    }

    /// `color checker(#fff, #222, 0.5)`: a pattern, the last one of a `color` argument; the
    /// argument becomes the pattern's first colour. `None` (reported) for an unknown pattern
    /// or its arguments' errors.
    fn color_pattern(&mut self, args: &mut [Arg]) -> Option<Option<Pattern>> {
        let mut pattern = None;
        for a in args {
            let is_color = a.name.as_ref().is_some_and(|n| n.name == "color");
            let crate::syntax::ExprKind::Call(call) = &a.value.kind else {
                continue;
            };
            if !is_color {
                continue;
            }
            let (p, first) = self.pattern(call)?;
            pattern = Some(p);
            a.value.kind =
                crate::syntax::ExprKind::Vector(Box::new([first.x, first.y, first.z].map(|c| {
                    crate::syntax::Expr {
                        kind: crate::syntax::ExprKind::Number {
                            value: c,
                            unit: None,
                        },
                        span: call.span,
                    }
                })));
        }
        Some(pattern)
    }

    /// A pattern's call, `checker(#fff, #222, 0.5)`: the pattern and its first colour.
    fn pattern(&mut self, call: &crate::syntax::Call) -> Option<(Pattern, glam::DVec3)> {
        let Some(&(pname, kind, _)) = PATTERNS.iter().find(|p| p.0 == call.name.name) else {
            let names = PATTERNS.iter().map(|p| p.0);
            let mut d = Diagnostic::error(
                call.name.span,
                format!("unknown pattern `{}`", call.name.name),
            )
            .label("not a pattern");
            d = match self.did_you_mean(&call.name.name, names.clone()) {
                Some(n) => d.help(format!("did you mean `{n}`?")),
                None => d.note(format!(
                    "a colour is `#rrggbb`, `(r, g, b)` or a pattern: {}",
                    names.collect::<Vec<_>>().join(", ")
                )),
            };
            self.diags.push(d);
            return None;
        };
        if let Some(block) = &call.block {
            let at = block.first().map_or(call.span, |e| e.span);
            self.diags.push(
                Diagnostic::error(at, format!("the pattern `{pname}` takes no block"))
                    .label("remove this block"),
            );
        }
        let v = self.bind(pname, PATTERN, &call.args, call.span)?;
        let pattern = Pattern {
            kind,
            other: v[1].vec(),
            scale: v[2].num(),
            octaves: v[3].num() as u32,
        };
        Some((pattern, v[0].vec()))
    }

    /// A material past the scene's limit, or reflecting and transmitting more than 1.
    fn material_limits(&mut self, name: &Ident, reflect: f64, transparent: f64, span: Span) {
        if self.materials.len() == super::MAX_MATERIALS {
            self.diags.push(
                Diagnostic::error(name.span, "the scene has too many materials")
                    .label("one material more than the limit")
                    .note(format!("the limit is {} materials: each is a branch of the shading the GPU driver compiles", super::MAX_MATERIALS)),
            );
        }
        if reflect + transparent > 1.0 {
            self.diags.push(
                Diagnostic::error(span, format!("`reflect {reflect}` and `transparent {transparent}` add up to more than 1"))
                    .label("more light leaves the surface than reaches it")
                    .note("the surface's own shading gets 1 − reflect − transparent of the light; lower one of them"),
            );
        }
    }
}
