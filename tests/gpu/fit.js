// The fitted-function case of tests/gpu_path.rs: each emitted WGSL function (brdfbake fit)
// evaluated in a WebGPU compute shader at the points the test serves at /cases.json
// (pairs of inputs), one vec4 per point back (the outputs, zero-padded).
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

async function main() {
    const cases = await (await fetch('/cases.json')).json();
    const adapter = navigator.gpu && await navigator.gpu.requestAdapter();
    const info = { adapter: adapter ? (adapter.info && (adapter.info.architecture || adapter.info.vendor)) || 'unknown' : null };
    if (adapter) {
        const device = await adapter.requestDevice();
        for (const c of cases) {
            try {
                await post(`/result/${c.id}`, (await run(device, c)).buffer, 'application/octet-stream');
            } catch (e) {
                await post(`/error/${c.id}`, String(e && e.stack || e), 'text/plain');
            }
        }
    } else {
        for (const c of cases) await post(`/error/${c.id}`, 'no WebGPU adapter', 'text/plain');
    }
    log.textContent = 'done';
    await post('/done', JSON.stringify(info), 'application/json');
}

main().catch(async (e) => {
    log.textContent = String(e && e.stack || e);
    await post('/fatal', String(e && e.stack || e), 'text/plain');
});
