// three.js (WebGL2) side of tests/gpu_path.rs: loading brdfbake's KTX2 tables and sampling
// them through the generated GLSL snippets. The regions between `docs:begin` and `docs:end`
// are quoted verbatim in docs/engines.md (a test checks it).
import * as THREE from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { read } from 'three/addons/libs/ktx-parse.module.js';

// docs:begin threejs-load
// A brdfbake .ktx2 table (1D, 2D, or 3D with "layout_3d": "volume") as a three.js texture.
async function loadTable(renderer, url) {
    const loader = new KTX2Loader().detectSupport(renderer);
    const texture = await loader.loadAsync(url); // DataTexture or Data3DTexture
    // KTX2Loader gives uncompressed textures NearestFilter: the snippets need linear filtering.
    texture.minFilter = THREE.LinearFilter;
    texture.magFilter = THREE.LinearFilter;
    texture.needsUpdate = true;
    // wrapS/wrapT/wrapR are ClampToEdgeWrapping and flipY is false already: as the snippets expect.
    return texture;
}
// docs:end

// docs:begin threejs-array
// A 3D table written with "layout_3d": "array": KTX2Loader would load only its first layer,
// so read the file with ktx-parse (shipped with three.js) and build the DataArrayTexture.
const VK_FORMATS = { // vkFormat -> [three.js format, type, typed array]
    100: [THREE.RedFormat, THREE.FloatType, Float32Array], // R32_SFLOAT
    103: [THREE.RGFormat, THREE.FloatType, Float32Array], // R32G32_SFLOAT
    109: [THREE.RGBAFormat, THREE.FloatType, Float32Array], // R32G32B32A32_SFLOAT
    76: [THREE.RedFormat, THREE.HalfFloatType, Uint16Array], // R16_SFLOAT
    83: [THREE.RGFormat, THREE.HalfFloatType, Uint16Array], // R16G16_SFLOAT
    97: [THREE.RGBAFormat, THREE.HalfFloatType, Uint16Array], // R16G16B16A16_SFLOAT
    9: [THREE.RedFormat, THREE.UnsignedByteType, Uint8Array], // R8_UNORM ("storage": "unorm8")
    16: [THREE.RGFormat, THREE.UnsignedByteType, Uint8Array], // R8G8_UNORM
    37: [THREE.RGBAFormat, THREE.UnsignedByteType, Uint8Array], // R8G8B8A8_UNORM
};
async function loadArrayTable(url) {
    const ktx = read(new Uint8Array(await (await fetch(url)).arrayBuffer()));
    const [format, type, Typed] = VK_FORMATS[ktx.vkFormat];
    const level = ktx.levels[0].levelData;
    const data = new Typed(level.buffer, level.byteOffset, level.byteLength / Typed.BYTES_PER_ELEMENT);
    const texture = new THREE.DataArrayTexture(data, ktx.pixelWidth, ktx.pixelHeight, ktx.layerCount);
    texture.format = format;
    texture.type = type;
    texture.minFilter = THREE.LinearFilter;
    texture.magFilter = THREE.LinearFilter;
    texture.needsUpdate = true;
    return texture;
}
// docs:end

// docs:begin threejs-shader
// The generated .glsl file's text goes into the fragment shader as written. RawShaderMaterial
// adds no precision statements: the snippet's own highp qualifiers are what makes it compile
// in GLSL ES 3.00. Declare the table's sampler uniform highp (sampler2D, sampler3D or
// sampler2DArray): GLSL ES has no default precision for the last two.
function lookupMaterial(snippet, samplerType, call, texture, points) {
    return new THREE.RawShaderMaterial({
        glslVersion: THREE.GLSL3,
        uniforms: { lut: { value: texture }, points: { value: points } },
        vertexShader: `in vec3 position;
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`,
        fragmentShader: `${snippet}
uniform highp ${samplerType} lut;
uniform highp sampler2D points;
out highp vec4 result;
void main() {
    highp vec4 x = texelFetch(points, ivec2(gl_FragCoord.xy), 0);
    result = ${call};
}`,
    });
}
// docs:end

const SAMPLERS = { '2d': 'sampler2D', '3d': 'sampler3D', array: 'sampler2DArray' };

// Samples `c.points` (x0, x1, x2, 0 per point) through `c.call` into an RGBA32F target and
// reads it back: a Float32Array of 4 values per point.
async function sample(renderer, texture, c) {
    const n = c.points.length / 4;
    const width = Math.min(n, 256);
    const height = Math.ceil(n / width);
    const data = new Float32Array(width * height * 4);
    data.set(c.points);
    const points = new THREE.DataTexture(data, width, height, THREE.RGBAFormat, THREE.FloatType);
    points.needsUpdate = true;
    const target = new THREE.WebGLRenderTarget(width, height, {
        type: THREE.FloatType, format: THREE.RGBAFormat, depthBuffer: false,
        minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
    });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 3, -1, 0, -1, 3, 0], 3));
    const material = lookupMaterial(c.snippet, SAMPLERS[c.layout], c.call, texture, points);
    const mesh = new THREE.Mesh(geometry, material);
    mesh.frustumCulled = false;
    const scene = new THREE.Scene();
    scene.add(mesh);
    renderer.setRenderTarget(target);
    renderer.render(scene, new THREE.Camera());
    renderer.setRenderTarget(null);
    const out = new Float32Array(width * height * 4);
    renderer.readRenderTargetPixels(target, 0, 0, width, height, out);
    for (const o of [points, target, geometry, material]) o.dispose();
    return out.subarray(0, n * 4);
}

export async function runWebGL(cases, report) {
    const canvas = document.createElement('canvas');
    const renderer = new THREE.WebGLRenderer({ canvas });
    renderer.debug.onShaderError = (gl, program, vs, fs) => {
        throw new Error('shader error: ' + gl.getProgramInfoLog(program) + ' ' + gl.getShaderInfoLog(fs));
    };
    const gl = renderer.getContext();
    const info = {
        renderer: gl.getParameter(gl.RENDERER),
        float_linear: gl.getExtension('OES_texture_float_linear') !== null,
        color_buffer_float: gl.getExtension('EXT_color_buffer_float') !== null,
        texture_norm16: gl.getExtension('EXT_texture_norm16') !== null,
    };
    for (const c of cases) {
        if (c.needs && gl.getExtension(c.needs) === null) {
            await report(c, null, 'skipped: no ' + c.needs);
            continue;
        }
        try {
            let texture;
            if (c.layout === 'array') {
                // the trap: KTX2Loader reads an array file as a 2D texture of its first layer
                const loaded = await new KTX2Loader().detectSupport(renderer).loadAsync(c.ktx2);
                info.ktx2loader_array = {
                    isDataArrayTexture: loaded.isDataArrayTexture === true,
                    isDataTexture: loaded.isDataTexture === true,
                    width: loaded.image.width, height: loaded.image.height,
                    depth: loaded.image.depth === undefined ? null : loaded.image.depth,
                };
                loaded.dispose();
                texture = await loadArrayTable(c.ktx2);
            } else {
                const raw = await new KTX2Loader().detectSupport(renderer).loadAsync(c.ktx2);
                info.ktx2loader_filter_nearest = raw.minFilter === THREE.NearestFilter && raw.magFilter === THREE.NearestFilter;
                raw.dispose();
                texture = await loadTable(renderer, c.ktx2);
            }
            await report(c, await sample(renderer, texture, c));
            texture.dispose();
        } catch (e) {
            await report(c, null, String(e && e.stack || e));
        }
    }
    renderer.dispose();
    return info;
}

// (for tests/gpu/ltc.js: two tables in one shader)
export { loadTable };
