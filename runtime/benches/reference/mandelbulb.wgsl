// mandelbulb.wgsl — hand-written reference for examples/mandelbulb.sdf, written for
// `sdfc bench --reference` so that sdfc's generated shader can be timed against what a person
// would write by hand (Shadertoy style: the usual power-8 distance estimator loop, powers by
// multiplication, no generic machinery).
//
// Scene: the power-8 Mandelbulb of Bálint & Valasek (2018), Fig. 4 (left), 10 iterations,
// bailout |z| > 2, estimate 0.5 · ln r · r / dr, its pole axis turned from z to y
// (rotate(x, −90°): the estimator sees (x, −z, y)). Outside the sphere of radius 2·2^(1/7)
// the field is |p| − 2^(1/7) (the escape sphere), as in sdfc.
//
// Tracer: basic sphere tracing (Hart), the scene's own `trace basic` line:
//   steps 256, epsilon 0.0005 (fixed), max_distance 6. Per step: budget test, one map(), hit if
//   d < 0.0005, t += d, stop when t > 6.
// The estimate counts as exact for the hit test (no hit confirmation), as in sdfc.
//
// Output: out[i] = (bitcast(t), steps | hit << 31), t where the ray stopped.

struct View {
    eye: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
    size: vec4<f32>,
    offset: vec4<u32>,
}

@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read_write> out: array<vec2<u32>>;

const STEPS: u32 = 256u;
const EPS: f32 = 0.0005;
const MAX_T: f32 = 6.0;

const ESCAPE_R: f32 = 1.1040895;   // 2^(1/7): the bulb lies inside this sphere

fn map(q: vec3<f32>) -> f32 {
    let c = vec3<f32>(q.x, -q.z, q.y);
    var r = length(c);
    if (r > 2.0 * ESCAPE_R) {
        return r - ESCAPE_R;
    }
    var z = c;
    var dr = 1.0;
    for (var i = 0; i < 10; i++) {
        if (r > 2.0) {
            break;
        }
        let theta = atan2(length(z.xy), z.z) * 8.0;
        let phi = atan2(z.y, z.x) * 8.0;
        let r2 = r * r;
        let r4 = r2 * r2;
        let r7 = r4 * r2 * r;
        dr = 8.0 * r7 * dr + 1.0;
        let st = sin(theta);
        z = (r7 * r) * vec3<f32>(st * cos(phi), st * sin(phi), cos(theta)) + c;
        r = length(z);
    }
    r = max(r, 1e-20);
    return 0.5 * log(r) * r / dr;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let px = gid.xy + view.offset.xy;
    if (px.x >= view.offset.z || px.y >= view.offset.w) {
        return;
    }
    let index = px.y * view.offset.z + px.x;

    let uv = (vec2<f32>(px) + 0.5) / view.size.xy * 2.0;
    let rd = normalize(view.forward.xyz + view.right.xyz * (uv.x - 1.0) + view.up.xyz * (1.0 - uv.y));
    let ro = view.eye.xyz;

    // The point is advanced with the step (p += rd·d), as sdfc does.
    var p = ro;
    var t = 0.0;
    var steps = 0u;
    var hit = 0u;
    loop {
        if (steps >= STEPS) {
            break;
        }
        let d = map(p);
        steps += 1u;
        if (d < EPS) {
            hit = 1u;
            break;
        }
        t += d;
        p += rd * d;
        if (t > MAX_T) {
            break;
        }
    }
    out[index] = vec2<u32>(bitcast<u32>(t), steps | (hit << 31u));
}
