// Runs the cases tests/gpu_path.rs serves at /cases.json and posts each result back as raw
// f32 bytes (4 values per point), then /done with what the runs found out.
import { runWebGL } from '/threejs.js';
import { runWebGPU } from '/webgpu.js';

const log = document.getElementById('log');

async function post(path, body, type) {
    const r = await fetch(path, { method: 'POST', body, headers: { 'Content-Type': type } });
    if (!r.ok) throw new Error(`POST ${path}: ${r.status}`);
}

async function report(c, values, error) {
    if (error !== undefined) {
        await post(`/error/${c.id}`, error, 'text/plain');
    } else {
        await post(`/result/${c.id}`, values.slice().buffer, 'application/octet-stream');
    }
}

async function main() {
    const cases = await (await fetch('/cases.json')).json();
    const info = {};
    info.webgl = await runWebGL(cases.filter((c) => c.api === 'webgl'), report);
    info.webgpu = await runWebGPU(cases.filter((c) => c.api === 'webgpu'), report);
    log.textContent = 'done';
    await post('/done', JSON.stringify(info), 'application/json');
}

main().catch(async (e) => {
    log.textContent = String(e && e.stack || e);
    await post('/fatal', String(e && e.stack || e), 'text/plain');
});
