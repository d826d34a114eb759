//! The cases of the extremes suite: one scene per case, with the tracer parameters it sets and
//! the share of pixels that may be wrong (a hole or a false hit) before the case fails.

/// One case of the suite.
pub struct Case {
    /// The row group in docs/stability.md.
    pub group: &'static str,
    /// The case, as the table names it.
    pub name: String,
    /// The scene (camera, trace block and shapes).
    pub source: String,
    /// Tracer parameters the case sets (`omega`, `beta`…); a tracer without one of them is
    /// not run on the case (its cell reads "—").
    pub params: Vec<(&'static str, String)>,
    /// Largest share of pixels that may be holes or false hits.
    pub tolerance: f64,
}

impl Case {
    fn new(group: &'static str, name: &str, source: &str, tolerance: f64) -> Case {
        Case {
            group,
            name: name.into(),
            source: source.into(),
            params: Vec::new(),
            tolerance,
        }
    }

    /// The case with a tracer parameter set.
    fn with(mut self, param: &'static str, value: &str) -> Case {
        self.params.push((param, value.into()));
        self
    }
}

/// The test scene: a sphere, a rotated box and a torus on a ground plane.
pub const BASE: &str = crate::common::EXTREMES_BASE;

/// [`BASE`] seen from the default viewpoint, with `trace` as its trace block.
fn base(trace: &str) -> String {
    format!("camera {{ eye (0, 3, -7) target (0, 0.5, 0) }}\n{trace}\n{BASE}")
}

/// [`BASE`] and its camera scaled by `s`.
pub fn scaled(s: f64) -> String {
    format!(
        "camera {{ eye (0, {}, {}) target (0, {}, 0) }}\ntrace basic {{ max_distance {} }}\nscale({s}) {{ union {{\n{BASE}\n}} }}",
        3.0 * s,
        -7.0 * s,
        0.5 * s,
        100.0 * s
    )
}

/// Every case, in the order of the table.
pub fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    for s in [1e-4, 1e-2, 1.0, 1e2, 1e4] {
        let name = format!("scene and camera × {s:e}");
        v.push(Case::new("scale", &name, &scaled(s), 0.01));
    }
    for d in [10.0f64, 1e3, 1e5] {
        // A sphere of radius 1 (d/1000 beyond 1e3: the narrowest field of view, 0.6°, would
        // make it less than a pixel) about a quarter of the image high.
        let r = (d / 1e3).max(1.0);
        let fov = (2.0 * (4.0 * r / d).atan().to_degrees()).max(0.6);
        let source = format!(
            "camera {{ eye (0, 0, {}) target (0, 0, 0) fov {fov}deg }}\ntrace basic {{ max_distance {} }}\nsphere({r})",
            -d,
            d * 2.0
        );
        let name = format!("camera {d:e} from a sphere of radius {r}");
        v.push(Case::new("distance", &name, &source, 0.01));
    }
    v.push(Case::new(
        "distance",
        "unit sphere and camera 1e5 from the origin",
        "camera { eye (100000, 1, -5) target (100000, 0, 0) }\ntrace basic { max_distance 50 }\nsphere(1) at (100000, 0, 0)\nplane(y, -1)",
        0.01,
    ));
    v.push(Case::new(
        "distance",
        "the same through a 0.6° field of view",
        "camera { eye (100000, 1, -5) target (100000, 0.99, 0) fov 0.6deg }\ntrace basic { max_distance 50 }\nsphere(1) at (100000, 0, 0)\nplane(y, -1)",
        0.01,
    ));
    v.push(Case::new(
        "grazing",
        "camera 0.01 above a plane",
        "camera { eye (0, 0.01, -5) target (0, 0.01, 5) }\ntrace basic { steps 400 }\nplane(y, 0)\nsphere(0.5) at (0, 0.5, 6)",
        0.01,
    ));
    v.push(Case::new(
        "grazing",
        "silhouettes: gap of 0.001 between two spheres",
        "camera { eye (0, 0, -6) target (0, 0, 0) fov 20deg }\nsphere(1) at (-1.0005, 0, 0)\nsphere(1) at (1.0005, 0, 0)",
        0.01,
    ));
    for e in ["0.0000001", "0.0001", "0.1"] {
        let source = base(&format!("trace basic {{ epsilon {e} }}"));
        // A small absolute ε makes rays grazing the ground near the horizon take more than
        // the 128 steps: holes where the budget runs out, up to 7% of this image (stated).
        let tolerance = if e == "0.1" { 0.01 } else { 0.1 };
        v.push(Case::new("ε", &format!("ε = {e}"), &source, tolerance));
    }
    for omega in ["1.0", "1.5", "1.99"] {
        let name = format!("ω = {omega}");
        v.push(Case::new("ω", &name, &base(""), 0.01).with("omega", omega));
    }
    // The other tracers' parameters at the ends of their ranges.
    for (param, value) in [
        ("omega", "0.5"),
        ("beta", "0"),
        ("linear", "16"),
        ("linear", "999"),
        ("refine", "0"),
        ("refine", "16"),
    ] {
        let name = format!("{param} = {value}");
        // Hybrid's linear steps of linear·ε(t) pass through anything thinner along the ray
        // (Liktor §5.4's trade): long steps go through thin parts of the scene (stated).
        let tolerance = if param == "linear" { 0.1 } else { 0.01 };
        v.push(Case::new("parameters", &name, &base(""), tolerance).with(param, value));
    }
    for steps in [1, 100000] {
        let source = base(&format!("trace basic {{ steps {steps} }}"));
        let tolerance = if steps == 1 { 1.0 } else { 0.01 };
        v.push(Case::new(
            "budget",
            &format!(
                "a budget of {steps} step{}",
                if steps == 1 { "" } else { "s" }
            ),
            &source,
            tolerance,
        ));
    }
    for (name, shape) in [
        ("zero-radius sphere", "sphere(0)"),
        ("zero-size box", "box(0)"),
        ("torus, minor radius > major", "torus(0.3, 0.6)"),
        ("zero-length capsule", "capsule(height = 0, radius = 0.5)"),
        ("rotation by 0°", "box(1) |> rotate(y, 0deg)"),
        ("rotation by 360°", "box(1) |> rotate(y, 360deg)"),
        (
            "zero-thickness shell of a plane",
            "plane(x, 0) |> onion(0) at (0.5, 0, 0)",
        ),
    ] {
        let source =
            format!("camera {{ eye (0, 1.5, -4) target (0, 0, 0) }}\n{shape}\nplane(y, -1)");
        v.push(Case::new("degenerate", name, &source, 0.01));
    }
    // Rays leaving a wall head-on: f grows by exactly the step, so the enhanced step's
    // denominator d + r₋ − r is 0 and the auto tracer's slope average tends to 1.
    let leaving = "camera { eye (0, 0, 0.05) target (0, 0, 1) fov 30deg }\nbox((20, 20, 0.1)) at (0, 0, -0.1)\nsphere(1) at (0, 0, 30)";
    let guards = "step guards";
    v.push(Case::new(guards, "leaving a wall head-on", leaving, 0.01));
    let small = leaving
        .replace("sphere(1)", "sphere(0.1)")
        .replace("30deg", "2deg");
    v.push(Case::new(
        guards,
        "leaving a wall towards a sphere of radius 0.1",
        &small,
        0.01,
    ));
    v.push(Case::new(guards, "leaving a wall head-on, β = 1", leaving, 0.01).with("beta", "1"));
    v.push(
        Case::new(guards, "leaving a wall head-on, ω = 1.99", leaving, 0.01).with("omega", "1.99"),
    );
    v.push(Case::new(
        "normals",
        "zero gradient: camera at a sphere's centre",
        "camera { eye (0, 0, 0) target (0, 0, 1) }\nsphere(3)",
        0.01,
    ));
    v.push(Case::new(
        "normals",
        "cusp: a cone's apex seen from above",
        "camera { eye (0, 3, 0.001) target (0, 0, 0) fov 10deg }\ncone(radius = 1, height = 2)",
        0.01,
    ));
    v.push(Case::new(
        "inside",
        "camera inside a solid",
        "camera { eye (0, 0, 0.5) target (0, 0, 1) }\nsphere(3)\nsphere(0.5) at (0, 0, 2)",
        0.01,
    ));
    v
}
