// The LTC area-light case of tests/gpu_path.rs: an `ltc` preset's two tables (the matrix
// table and the norm/fresnel table) uploaded as webgpu.js and threejs.js upload every table,
// and the generated area-light functions evaluated for every (shading point, light polygon,
// roughness, f0) the test serves at /cases.json: WGSL in a WebGPU compute shader, GLSL in a
// three.js RawShaderMaterial (WebGL2) rendering to an RGBA32F target. Each case posts 3 vec4
// per point: the matrix texel, (norm, fresnel, integral, n.v), the specular.
import * as THREE from 'three';
import { createTableView, tableDevice, tableSampler } from '/webgpu.js';
import { loadTable } from '/threejs.js';

const log = document.getElementById('log');

async function post(path, body, type) {
    const r = await fetch(path, { method: 'POST', body, headers: { 'Content-Type': type } });
    if (!r.ok) throw new Error(`POST ${path}: ${r.status}`);
}

// A point: 7 vec4 = (n, roughness), (v, f0), (pos, 0), p0, p1, p2, p3 (p3 = p0: a triangle).
function module(c) {
    return `${c.matrix_snippet}
${c.schlick_snippet}
@group(0) @binding(0) var matrix_table: texture_2d<f32>;
@group(0) @binding(1) var schlick_table: texture_2d<f32>;
@group(0) @binding(2) var table_sampler: sampler;
@group(0) @binding(3) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> results: array<vec4<f32>>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&points) / 7u) { return; }
    let b = 7u * i;
    let n = points[b].xyz;
    let r = points[b].w;
    let v = points[b + 1u].xyz;
    let f0 = points[b + 1u].w;
    let nv = dot(n, v);
    let minv = ${c.prefix_matrix}_ltc_minv(matrix_table, table_sampler, r, nv);
    let e = ${c.prefix_matrix}_ltc_polygon(minv, n, v, points[b + 2u].xyz,
        points[b + 3u].xyz, points[b + 4u].xyz, points[b + 5u].xyz, points[b + 6u].xyz);
    let t2 = ${c.prefix_schlick}_lookup(schlick_table, table_sampler, r, nv);
    let w = ${c.prefix_schlick}_schlick_weight(schlick_table, table_sampler, r, nv,
        vec3<f32>(f0, 0.5, 0.0), vec3<f32>(1.0));
    results[3u * i] = ${c.prefix_matrix}_lookup(matrix_table, table_sampler, r, nv);
    results[3u * i + 1u] = vec4<f32>(t2.x, t2.y, e, nv);
    results[3u * i + 2u] = vec4<f32>(w * max(e, 0.0), 0.0);
}
`;
}

async function run(device, c) {
    const n = c.points.length / 28;
    const views = [];
    for (const url of [c.matrix_ktx2, c.schlick_ktx2]) {
        views.push(createTableView(device, await (await fetch(url)).arrayBuffer()));
    }
    const shader = device.createShaderModule({ code: module(c) });
    const messages = (await shader.getCompilationInfo()).messages.filter((m) => m.type === 'error');
    if (messages.length > 0) throw new Error('WGSL does not compile: ' + messages.map((m) => m.message).join('; '));
    const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module: shader, entryPoint: 'main' } });
    const points = device.createBuffer({ size: n * 112, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(points, 0, new Float32Array(c.points));
    const size = n * 48;
    const results = device.createBuffer({ size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const readback = device.createBuffer({ size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    device.pushErrorScope('validation');
    const bind = device.createBindGroup({
        layout: pipeline.getBindGroupLayout(0),
        entries: [
            { binding: 0, resource: views[0] },
            { binding: 1, resource: views[1] },
            { binding: 2, resource: tableSampler(device) },
            { binding: 3, resource: { buffer: points } },
            { binding: 4, resource: { buffer: results } },
        ],
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

// WebGL2: the points as a 7 x N RGBA32F texture (row i = point i), the results in a 3 x N
// target (row i = the 3 vec4 of point i), so that they read back in the WebGPU order.
function glslShader(c) {
    const m = c.prefix_matrix, s = c.prefix_schlick;
    return `${c.matrix_snippet}
${c.schlick_snippet}
uniform highp sampler2D matrix_table;
uniform highp sampler2D schlick_table;
uniform highp sampler2D points;
out highp vec4 result;
void main() {
    highp ivec2 p = ivec2(gl_FragCoord.xy);
    highp vec4 a = texelFetch(points, ivec2(0, p.y), 0);
    highp vec4 b = texelFetch(points, ivec2(1, p.y), 0);
    highp vec3 n = a.xyz;
    highp vec3 v = b.xyz;
    highp float nv = dot(n, v);
    highp mat3 minv = ${m}_ltc_minv(matrix_table, a.w, nv);
    highp float e = ${m}_ltc_polygon(minv, n, v, texelFetch(points, ivec2(2, p.y), 0).xyz,
        texelFetch(points, ivec2(3, p.y), 0).xyz, texelFetch(points, ivec2(4, p.y), 0).xyz,
        texelFetch(points, ivec2(5, p.y), 0).xyz, texelFetch(points, ivec2(6, p.y), 0).xyz);
    highp vec4 t2 = ${s}_lookup(schlick_table, a.w, nv);
    highp vec3 w = ${s}_schlick_weight(schlick_table, a.w, nv, vec3(b.w, 0.5, 0.0), vec3(1.0));
    if (p.x == 0) {
        result = ${m}_lookup(matrix_table, a.w, nv);
    } else if (p.x == 1) {
        result = vec4(t2.x, t2.y, e, nv);
    } else {
        result = vec4(w * max(e, 0.0), 0.0);
    }
}`;
}

async function runWebGL(renderer, c) {
    const n = c.points.length / 28;
    const points = new THREE.DataTexture(new Float32Array(c.points), 7, n, THREE.RGBAFormat, THREE.FloatType);
    points.needsUpdate = true;
    const matrix = await loadTable(renderer, c.matrix_ktx2);
    const schlick = await loadTable(renderer, c.schlick_ktx2);
    const target = new THREE.WebGLRenderTarget(3, n, {
        type: THREE.FloatType, format: THREE.RGBAFormat, depthBuffer: false,
        minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
    });
    const material = new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3,
        uniforms: { matrix_table: { value: matrix }, schlick_table: { value: schlick }, points: { value: points } },
        vertexShader: `in vec3 position;
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`,
        fragmentShader: glslShader(c),
    });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 3, -1, 0, -1, 3, 0], 3));
    const mesh = new THREE.Mesh(geometry, material);
    mesh.frustumCulled = false;
    const scene = new THREE.Scene();
    scene.add(mesh);
    renderer.setRenderTarget(target);
    renderer.render(scene, new THREE.Camera());
    renderer.setRenderTarget(null);
    const out = new Float32Array(3 * n * 4);
    renderer.readRenderTargetPixels(target, 0, 0, 3, n, out);
    for (const o of [points, matrix, schlick, target, geometry, material]) o.dispose();
    return out;
}

async function main() {
    const cases = await (await fetch('/cases.json')).json();
    const renderer = new THREE.WebGLRenderer({ canvas: document.createElement('canvas') });
    renderer.debug.onShaderError = (gl, program, vs, fs) => {
        throw new Error('shader error: ' + gl.getProgramInfoLog(program) + ' ' + gl.getShaderInfoLog(fs));
    };
    for (const c of cases.filter((c) => c.api === 'webgl')) {
        try {
            await post(`/result/${c.id}`, (await runWebGL(renderer, c)).buffer, 'application/octet-stream');
        } catch (e) {
            await post(`/error/${c.id}`, String(e && e.stack || e), 'text/plain');
        }
    }
    renderer.dispose();
    const adapter = navigator.gpu && await navigator.gpu.requestAdapter();
    const info = { adapter: adapter ? (adapter.info && (adapter.info.architecture || adapter.info.vendor)) || 'unknown' : null };
    if (adapter) {
        info.float32_filterable = adapter.features.has('float32-filterable');
        const device = await tableDevice();
        for (const c of cases.filter((c) => c.api === 'webgpu')) {
            try {
                await post(`/result/${c.id}`, (await run(device, c)).buffer, 'application/octet-stream');
            } catch (e) {
                await post(`/error/${c.id}`, String(e && e.stack || e), 'text/plain');
            }
        }
    } else {
        for (const c of cases.filter((c) => c.api === 'webgpu')) await post(`/error/${c.id}`, 'no WebGPU adapter', 'text/plain');
    }
    log.textContent = 'done';
    await post('/done', JSON.stringify(info), 'application/json');
}

main().catch(async (e) => {
    log.textContent = String(e && e.stack || e);
    await post('/fatal', String(e && e.stack || e), 'text/plain');
});
