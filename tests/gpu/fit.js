// The fitted-function case of tests/gpu_path.rs: each emitted function (brdfbake fit)
// evaluated at the points the test serves at /cases.json (pairs of inputs), one vec4 per
// point back (the outputs, zero-padded): WGSL in a WebGPU compute shader, GLSL ES 3.00 in a
// WebGL2 fragment shader writing an RGBA32F target (one point per pixel).
const log = document.getElementById('log');

async function post(path, body, type) {
    const r = await fetch(path, { method: 'POST', body, headers: { 'Content-Type': type } });
    if (!r.ok) throw new Error(`POST ${path}: ${r.status}`);
}

function module(c) {
    return `${c.wgsl}
@group(0) @binding(0) var<storage, read> points: array<vec2<f32>>;
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&points)) { return; }
    let y = ${c.name}(points[i].x, points[i].y);
    results[i] = ${c.widen};
}
`;
}

async function run(device, c) {
    const n = c.points.length / 2;
    const shader = device.createShaderModule({ code: module(c) });
    const messages = (await shader.getCompilationInfo()).messages.filter((m) => m.type === 'error');
    if (messages.length > 0) throw new Error('WGSL does not compile: ' + messages.map((m) => m.message).join('; '));
    const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module: shader, entryPoint: 'main' } });
    const points = device.createBuffer({ size: n * 8, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(points, 0, new Float32Array(c.points));
    const size = n * 16;
    const results = device.createBuffer({ size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const readback = device.createBuffer({ size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    device.pushErrorScope('validation');
    const bind = device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [{ binding: 0, resource: { buffer: points } }, { binding: 1, resource: { buffer: results } }],
    });
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, bind);
    pass.dispatchWorkgroups(Math.ceil(n / 64));
    pass.end();
    encoder.copyBufferToBuffer(results, 0, readback, 0, size);
    device.queue.submit([encoder.finish()]);
    const error = await device.popErrorScope();
    if (error) throw new Error('WebGPU validation: ' + error.message);
    await readback.mapAsync(GPUMapMode.READ);
    const out = new Float32Array(readback.getMappedRange().slice(0));
    readback.unmap();
    for (const b of [points, results, readback]) b.destroy();
    return out;
}

// GLSL: one GL_POINTS vertex per point, at pixel (i mod W, i div W); the inputs reach the
// fragment shader unchanged (flat) and the function runs there, highp (f32).
function runGlsl(c) {
    const n = c.points.length / 2;
    const W = 64;
    const H = Math.ceil(n / W);
    const canvas = document.createElement('canvas');
    canvas.width = W;
    canvas.height = H;
    const gl = canvas.getContext('webgl2', { antialias: false });
    if (!gl) throw new Error('no WebGL2 context');
    if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('no EXT_color_buffer_float');
    const vs = `#version 300 es
precision highp float;
in vec2 point;
flat out vec2 p;
void main() {
    float i = float(gl_VertexID);
    float x = mod(i, ${W}.0);
    float y = floor(i / ${W}.0);
    p = point;
    gl_Position = vec4((x + 0.5) / ${W}.0 * 2.0 - 1.0, (y + 0.5) / ${H}.0 * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
`;
    const fs = `#version 300 es
precision highp float;
${c.glsl}
flat in vec2 p;
out vec4 color;
void main() {
    color = ${c.widen_glsl.replace('y', `${c.name}(p.x, p.y)`)};
}
`;
    const compile = (type, src) => {
        const sh = gl.createShader(type);
        gl.shaderSource(sh, src);
        gl.compileShader(sh);
        if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error('GLSL does not compile: ' + gl.getShaderInfoLog(sh));
        return sh;
    };
    const prog = gl.createProgram();
    gl.attachShader(prog, compile(gl.VERTEX_SHADER, vs));
    gl.attachShader(prog, compile(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error('GLSL does not link: ' + gl.getProgramInfoLog(prog));
    const tex = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, W, H);
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, tex, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) throw new Error('RGBA32F target incomplete');
    const buf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, buf);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(c.points), gl.STATIC_DRAW);
    const loc = gl.getAttribLocation(prog, 'point');
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, 2, gl.FLOAT, false, 0, 0);
    gl.viewport(0, 0, W, H);
    gl.useProgram(prog);
    gl.disable(gl.BLEND);
    gl.drawArrays(gl.POINTS, 0, n);
    const out = new Float32Array(W * H * 4);
    gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, out);
    const err = gl.getError();
    if (err !== gl.NO_ERROR) throw new Error('WebGL error ' + err);
    return out.slice(0, n * 4);
}

async function main() {
    const cases = await (await fetch('/cases.json')).json();
    const adapter = navigator.gpu && await navigator.gpu.requestAdapter();
    const info = { adapter: adapter ? (adapter.info && (adapter.info.architecture || adapter.info.vendor)) || 'unknown' : null };
    for (const c of cases.filter((c) => c.glsl)) {
        try {
            await post(`/result/${c.id}`, runGlsl(c).buffer, 'application/octet-stream');
        } catch (e) {
            await post(`/error/${c.id}`, String(e && e.stack || e), 'text/plain');
        }
    }
    const wgsl = cases.filter((c) => c.wgsl);
    if (adapter) {
        const device = await adapter.requestDevice();
        for (const c of wgsl) {
            try {
                await post(`/result/${c.id}`, (await run(device, c)).buffer, 'application/octet-stream');
            } catch (e) {
                await post(`/error/${c.id}`, String(e && e.stack || e), 'text/plain');
            }
        }
    } else {
        for (const c of wgsl) await post(`/error/${c.id}`, 'no WebGPU adapter', 'text/plain');
    }
    log.textContent = 'done';
    await post('/done', JSON.stringify(info), 'application/json');
}

main().catch(async (e) => {
    log.textContent = String(e && e.stack || e);
    await post('/fatal', String(e && e.stack || e), 'text/plain');
});
