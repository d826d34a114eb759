// trivial.wgsl — hand-written reference for examples/bench/trivial.sdf: the camera ray and a
// sphere-tracing loop of one step on a unit sphere, as `trace basic { steps 1 }` does
// (ε = max(pixel·t, 4e-5), the floor 1e-5·|eye − target|; with one step no ray can hit).
// Beside bare.wgsl (no tracing at all), it splits a trivial frame's time into the harness's
// fixed cost and the per-pixel work.

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

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let px = gid.xy + view.offset.xy;
    if (px.x >= view.offset.z || px.y >= view.offset.w) {
        return;
    }
    let uv = (vec2<f32>(px) + 0.5) / view.size.xy * 2.0;
    let rd = normalize(view.forward.xyz + view.right.xyz * (uv.x - 1.0) + view.up.xyz * (1.0 - uv.y));
    var p = view.eye.xyz;
    var t = 0.0;
    var steps = 0u;
    var hit = 0u;
    loop {
        if (steps >= 1u) {
            break;
        }
        let d = length(p) - 1.0;
        steps += 1u;
        if (d < max(view.size.z * t, 0.00004)) {
            hit = 1u;
            break;
        }
        t += d;
        p += rd * d;
        if (t > 100.0) {
            break;
        }
    }
    out[px.y * view.offset.z + px.x] = vec2<u32>(bitcast<u32>(t), steps | (hit << 31u));
}
