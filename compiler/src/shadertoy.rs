//! The Shadertoy entry (`sdfc emit --entry shadertoy`): the library as GLSL ES 3.00 without
//! what Shadertoy supplies itself (`#version`, precisions, `main`), and a `mainImage` that
//! sets the parameters (their defaults, `time` from `iTime`), orbits the scene's camera with
//! `iMouse` and draws each pixel with `color`, encoded to sRGB. Pasteable as it is.

use crate::scene::{ParamKind, Scene};

/// The Shadertoy shader of `scene` with tracer settings `options`: the library compiled with
/// private parameters, written as GLSL ES 3.00, wrapped. (A scene with baked parts declares a
/// `sampler3D` uniform per volume, which Shadertoy cannot bind: `sdfc emit` refuses those.)
pub fn shader(
    scene: &Scene,
    options: &crate::lower::tracer::Options,
) -> Result<String, crate::emit::InternalError> {
    use crate::emit::{self, GlslVersion, Output, Settings, Target};
    let options = crate::lower::tracer::Options {
        private_params: true,
        ..*options
    };
    let (m, info) = emit::module(scene, crate::lower::Entry::Library, &options)?;
    let settings = Settings {
        glsl_version: GlslVersion::Es300,
        ..Settings::default()
    };
    match emit::write_with(
        &m,
        &info,
        Target::Glsl,
        crate::lower::Entry::Library,
        &settings,
    )? {
        Output::Text(library) => Ok(wrap(&library, scene)),
        Output::Binary(_) => unreachable!("GLSL is text"),
    }
}

/// The Shadertoy shader from the GLSL ES 3.00 library text of a module compiled with
/// `Options::private_params`.
pub fn wrap(library: &str, scene: &Scene) -> String {
    let mut out = String::from(
        "// Written by sdfc (`sdfc emit --entry shadertoy`): paste into Shadertoy's Image tab.\n\
         // Drag with the mouse to turn the camera around its target.\n",
    );
    let mut lines = library.lines().peekable();
    while let Some(line) = lines.next() {
        let t = line.trim_start();
        if t.starts_with("#version") || t.starts_with("precision ") {
            continue;
        }
        // The placeholder entry point (it only loads the globals) goes: Shadertoy has `main`.
        if t.starts_with("void main()") {
            for rest in lines.by_ref() {
                if rest.starts_with('}') {
                    break;
                }
            }
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out.push_str(&main_image(scene));
    out
}

/// A float literal GLSL ES accepts.
fn float(x: f64) -> String {
    let s = format!("{:?}", x as f32);
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

fn vec3(v: glam::DVec3) -> String {
    format!("vec3({}, {}, {})", float(v.x), float(v.y), float(v.z))
}

fn main_image(scene: &Scene) -> String {
    let c = &scene.camera;
    let values: Vec<String> = scene
        .params
        .iter()
        .map(|p| match p.kind {
            // (Wrapped into its declared range, where λ and bounds hold.)
            _ if p.name == crate::check::TIME => match p.range {
                Some((lo, hi)) if hi.x > lo.x => {
                    format!("{} + mod(iTime, {})", float(lo.x), float(hi.x - lo.x))
                }
                Some((lo, _)) => float(lo.x),
                None => "iTime".to_string(),
            },
            ParamKind::Number | ParamKind::Angle => float(p.default.x),
            ParamKind::Vector | ParamKind::Color => vec3(p.default),
        })
        .collect();
    let set_params = if values.is_empty() {
        String::new()
    } else {
        format!("    params = Params({});\n", values.join(", "))
    };
    format!(
        "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) {{\n\
         {set_params}\
         \x20   vec3 target = {target};\n\
         \x20   vec3 offset = {eye} - target;\n\
         \x20   float r = length(offset);\n\
         \x20   vec3 eye = {eye};\n\
         \x20   if (iMouse.z > 0.0) {{\n\
         \x20       float yaw = (iMouse.x / iResolution.x - 0.5) * 6.2831853;\n\
         \x20       float pitch = (iMouse.y / iResolution.y - 0.5) * 3.0;\n\
         \x20       float azimuth = atan(offset.x, offset.z) + yaw;\n\
         \x20       float elevation = clamp(asin(offset.y / r) + pitch, -1.5, 1.5);\n\
         \x20       eye = target + r * vec3(cos(elevation) * sin(azimuth), sin(elevation), cos(elevation) * cos(azimuth));\n\
         \x20   }}\n\
         \x20   vec3 forward = normalize(target - eye);\n\
         \x20   vec3 right = normalize(cross(forward, {up}));\n\
         \x20   vec3 up = cross(right, forward);\n\
         \x20   float t = {tan};\n\
         \x20   // The ray of `sdfc render`'s camera (docs/interface.md); fragCoord's y grows upwards.\n\
         \x20   vec2 uv = 2.0 * fragCoord / iResolution.xy - 1.0;\n\
         \x20   vec3 rd = normalize(forward + right * (t * iResolution.x / iResolution.y) * uv.x + up * t * uv.y);\n\
         \x20   vec4 c = color(eye, rd, t / iResolution.y);\n\
         \x20   vec3 lin = clamp(c.rgb, 0.0, 1.0);\n\
         \x20   vec3 srgb = mix(lin * 12.92, 1.055 * pow(lin, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, lin));\n\
         \x20   fragColor = vec4(srgb, 1.0);\n\
         }}\n",
        target = vec3(c.target),
        eye = vec3(c.eye),
        up = vec3(c.up),
        tan = float((c.fov / 2.0).tan()),
    )
}
