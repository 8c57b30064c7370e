// WebGPU side of tests/gpu_path.rs: brdfbake's KTX2 tables as WebGPU textures, sampled
// through the generated WGSL snippets in a compute shader. The regions between `docs:begin`
// and `docs:end` are quoted verbatim in docs/engines.md (a test checks it).
import { read } from 'three/addons/libs/ktx-parse.module.js';

// docs:begin webgpu-texture
// vkFormat of a brdfbake .ktx2 -> [WebGPU format, components]
const WEBGPU_FORMATS = {
    100: ['r32float', 1], 103: ['rg32float', 2], 109: ['rgba32float', 4],
    76: ['r16float', 1], 83: ['rg16float', 2], 97: ['rgba16float', 4],
    9: ['r8unorm', 1], 16: ['rg8unorm', 2], 37: ['rgba8unorm', 4], // "storage": "unorm8"
    // "storage": "unorm16": only with the 'texture-formats-tier1' feature, and not filterable
    70: ['r16unorm', 1], 77: ['rg16unorm', 2], 91: ['rgba16unorm', 4],
};
// A brdfbake .ktx2 file (an ArrayBuffer) as a texture view: 2D (1D and 2D tables), 3D
// ("layout_3d": "volume") or 2D array ("layout_3d": "array"). Rows upload in file order: no flip.
function createTableView(device, ktx2) {
    const ktx = read(new Uint8Array(ktx2));
    const [format, components] = WEBGPU_FORMATS[ktx.vkFormat];
    const volume = ktx.pixelDepth > 0;
    const size = [ktx.pixelWidth, ktx.pixelHeight, Math.max(ktx.pixelDepth, ktx.layerCount, 1)];
    const texture = device.createTexture({
        format, size, dimension: volume ? '3d' : '2d',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
    });
    const bytesPerRow = ktx.pixelWidth * components * ktx.typeSize;
    device.queue.writeTexture({ texture }, ktx.levels[0].levelData,
        { bytesPerRow, rowsPerImage: ktx.pixelHeight }, size);
    return texture.createView({ dimension: volume ? '3d' : ktx.layerCount > 0 ? '2d-array' : '2d' });
}
// 32-bit float textures are filterable only on a device created with 'float32-filterable'
// (an optional feature); f16 tables ("storage": "f16") filter on every device.
async function tableDevice() {
    const adapter = await navigator.gpu.requestAdapter();
    const f32 = adapter.features.has('float32-filterable');
    return adapter.requestDevice({ requiredFeatures: f32 ? ['float32-filterable'] : [] });
}
// Linear filtering, clamp-to-edge (the default address mode), no mipmaps.
function tableSampler(device) {
    return device.createSampler({ magFilter: 'linear', minFilter: 'linear' });
}
// docs:end

const TEXTURE_TYPES = { '2d': 'texture_2d<f32>', '3d': 'texture_3d<f32>', array: 'texture_2d_array<f32>' };

// The WGSL module: the generated snippet as written, bindings, and a compute entry point
// evaluating `c.call` at every point.
function module(c) {
    return `${c.snippet}
@group(0) @binding(0) var table: ${TEXTURE_TYPES[c.layout]};
@group(0) @binding(1) var table_sampler: sampler;
@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> results: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&points)) { return; }
    let x = points[i];
    results[i] = ${c.call};
}
`;
}

async function sample(device, c, ktx2) {
    const n = c.points.length / 4;
    const view = createTableView(device, ktx2);
    const shader = device.createShaderModule({ code: module(c) });
    const messages = (await shader.getCompilationInfo()).messages.filter((m) => m.type === 'error');
    if (messages.length > 0) throw new Error('WGSL does not compile: ' + messages.map((m) => m.message).join('; '));
    const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module: shader, entryPoint: 'main' } });
    const points = device.createBuffer({ size: n * 16, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(points, 0, new Float32Array(c.points));
    const results = device.createBuffer({ size: n * 16, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const readback = device.createBuffer({ size: n * 16, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    device.pushErrorScope('validation');
    const bind = device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [
            { binding: 0, resource: view },
            { binding: 1, resource: tableSampler(device) },
            { binding: 2, resource: { buffer: points } },
            { binding: 3, resource: { buffer: results } },
        ],
    });
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, bind);
    pass.dispatchWorkgroups(Math.ceil(n / 64));
    pass.end();
    encoder.copyBufferToBuffer(results, 0, readback, 0, n * 16);
    device.queue.submit([encoder.finish()]);
    const error = await device.popErrorScope();
    if (error) throw new Error('WebGPU validation: ' + error.message);
    await readback.mapAsync(GPUMapMode.READ);
    const out = new Float32Array(readback.getMappedRange().slice(0));
    readback.unmap();
    for (const b of [points, results, readback]) b.destroy();
    return out;
}

export async function runWebGPU(cases, report) {
    const info = {};
    const adapter = navigator.gpu && await navigator.gpu.requestAdapter();
    if (!adapter) {
        for (const c of cases) await report(c, null, 'no WebGPU adapter');
        return { adapter: null };
    }
    info.adapter = adapter.info ? adapter.info.architecture || adapter.info.vendor : 'unknown';
    info.float32_filterable = adapter.features.has('float32-filterable');
    info.texture_formats_tier1 = adapter.features.has('texture-formats-tier1');
    const withF32 = await tableDevice();
    const withoutF32 = await adapter.requestDevice();
    for (const c of cases) {
        try {
            const ktx2 = await (await fetch(c.ktx2)).arrayBuffer();
            await report(c, await sample(c.float32_filterable ? withF32 : withoutF32, c, ktx2));
        } catch (e) {
            await report(c, null, String(e && e.stack || e));
        }
    }
    return info;
}

// (for tests/gpu/ltc.js: two tables in one shader)
export { createTableView, tableDevice, tableSampler };
