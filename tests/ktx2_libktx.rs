//! KTX2 files written by brdfbake, read back by Khronos' own KTX-Software (libktx v4.0.0,
//! built from source by the `libktx-rs-sys` dev-dependency; needs `cmake`, which CI installs
//! in .ci/run), with the `ktx2` crate's reader as a second opinion, and checked by Khronos'
//! validator `ktx2check` (built by the same CMake build):
//!
//! - libktx loads each file (`ktxTexture2_CreateFromMemory` with the image data) and reports
//!   the expected vkFormat, dimensions, layers, levels, faces and orientation;
//! - the Data Format Descriptor is byte-identical to the one libktx builds for that vkFormat
//!   (`ktxTexture2_Create`), and libktx derives the expected component info and transfer
//!   function from it;
//! - the key/value data hold exactly `KTXorientation` and `KTXwriter`, NUL-terminated;
//! - every texel, located through libktx's own image offsets and row pitch, has the bytes of
//!   the table's value (f32 exactly, f16 as `half::f16::from_f32`, UNORM8/UNORM16 as the code
//!   computed here — the nearest integer to value × (2ⁿ − 1), ties to even —, padding alpha
//!   1.0 or the largest code);
//! - `ktx2check --warn-as-error` accepts the file.

use brdfbake::encode::ktx2::{Ktx2Encoder, Supercompression, WRITER};
use brdfbake::encode::{EncodeError, Encoder};
use brdfbake::lut::{Channel, Lut};
use brdfbake::table::Storage;
use half::f16;
use libktx_rs_sys as sys;
use std::ffi::{CStr, CString};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::ptr;

#[path = "common/luts.rs"]
mod luts;
use luts::{unorm_code, value, values_for};

/// A synthetic table of `channels` channels (named E, A, B, cloth).
fn lut(sizes: &[usize], channels: usize, f: impl Fn([usize; 3], usize) -> f32) -> Lut {
    luts::lut(sizes, &["E", "A", "B", "cloth"][..channels], f)
}

fn encoder(storage: Storage, array_3d: bool) -> Ktx2Encoder {
    Ktx2Encoder {
        storage,
        table_name: "test-table".into(),
        array_3d,
        supercompression: Supercompression::None,
    }
}

/// A texture libktx loaded; destroyed on drop.
struct Texture(*mut sys::ktxTexture2);

impl Texture {
    fn from_memory(bytes: &[u8]) -> Texture {
        let mut tex: *mut sys::ktxTexture2 = ptr::null_mut();
        let rc = unsafe {
            sys::ktxTexture2_CreateFromMemory(
                bytes.as_ptr(),
                bytes.len(),
                sys::ktxTextureCreateFlagBits_KTX_TEXTURE_CREATE_LOAD_IMAGE_DATA_BIT,
                &mut tex,
            )
        };
        assert_eq!(
            rc,
            sys::ktx_error_code_e_KTX_SUCCESS,
            "libktx: {}",
            error(rc)
        );
        assert!(!tex.is_null());
        Texture(tex)
    }

    /// A texture libktx creates itself, without storage, for `vk_format`.
    fn create(vk_format: u32) -> Texture {
        let mut info = sys::ktxTextureCreateInfo {
            glInternalformat: 0,
            vkFormat: vk_format,
            pDfd: ptr::null_mut(),
            baseWidth: 4,
            baseHeight: 4,
            baseDepth: 1,
            numDimensions: 2,
            numLevels: 1,
            numLayers: 1,
            numFaces: 1,
            isArray: false,
            generateMipmaps: false,
        };
        let mut tex: *mut sys::ktxTexture2 = ptr::null_mut();
        let rc = unsafe {
            sys::ktxTexture2_Create(
                &mut info,
                sys::ktxTextureCreateStorageEnum_KTX_TEXTURE_CREATE_NO_STORAGE,
                &mut tex,
            )
        };
        assert_eq!(
            rc,
            sys::ktx_error_code_e_KTX_SUCCESS,
            "libktx: {}",
            error(rc)
        );
        Texture(tex)
    }

    fn get(&self) -> &sys::ktxTexture2 {
        unsafe { &*self.0 }
    }

    /// The DFD, including its leading total size.
    fn dfd(&self) -> Vec<u8> {
        let p = self.get().pDfd;
        assert!(!p.is_null());
        let len = unsafe { *p } as usize;
        unsafe { std::slice::from_raw_parts(p as *const u8, len) }.to_vec()
    }

    /// The keys of the key/value data, in libktx's order.
    fn keys(&self) -> Vec<String> {
        let mut keys = Vec::new();
        let mut entry = self.get().kvDataHead;
        while !entry.is_null() {
            let mut len = 0;
            let mut key: *mut std::os::raw::c_char = ptr::null_mut();
            let rc = unsafe { sys::ktxHashListEntry_GetKey(entry, &mut len, &mut key) };
            assert_eq!(rc, sys::ktx_error_code_e_KTX_SUCCESS);
            keys.push(unsafe { CStr::from_ptr(key) }.to_str().unwrap().to_string());
            entry = unsafe { sys::ktxHashList_Next(entry) };
        }
        keys
    }

    /// A key's value bytes as stored (including any NUL), or `None`.
    fn value(&self, key: &str) -> Option<Vec<u8>> {
        let key = CString::new(key).unwrap();
        let mut len = 0;
        let mut value: *mut std::os::raw::c_void = ptr::null_mut();
        let rc = unsafe {
            sys::ktxHashList_FindValue(
                &mut (*self.0).kvDataHead,
                key.as_ptr(),
                &mut len,
                &mut value,
            )
        };
        (rc == sys::ktx_error_code_e_KTX_SUCCESS).then(|| {
            unsafe { std::slice::from_raw_parts(value as *const u8, len as usize) }.to_vec()
        })
    }

    fn image_offset(&self, layer: u32, face_slice: u32) -> usize {
        let mut offset = 0;
        let rc = unsafe {
            let f = (*self.get().vtbl).GetImageOffset.unwrap();
            f(
                self.0 as *mut sys::ktxTexture,
                0,
                layer,
                face_slice,
                &mut offset,
            )
        };
        assert_eq!(
            rc,
            sys::ktx_error_code_e_KTX_SUCCESS,
            "libktx: {}",
            error(rc)
        );
        offset
    }

    /// The bytes of one image (one slice, layer or 2D image) of level 0.
    fn image_size(&self) -> usize {
        unsafe {
            let f = (*self.get().vtbl).GetImageSize.unwrap();
            f(self.0 as *mut sys::ktxTexture, 0)
        }
    }

    /// The texture as libktx's own writer serializes it.
    fn write_to_memory(&self) -> Vec<u8> {
        let mut p: *mut u8 = ptr::null_mut();
        let mut n = 0;
        let rc = unsafe {
            let f = (*self.get().vtbl).WriteToMemory.unwrap();
            f(self.0 as *mut sys::ktxTexture, &mut p, &mut n)
        };
        assert_eq!(
            rc,
            sys::ktx_error_code_e_KTX_SUCCESS,
            "libktx: {}",
            error(rc)
        );
        let bytes = unsafe { std::slice::from_raw_parts(p, n) }.to_vec();
        unsafe { libc_free(p as *mut std::os::raw::c_void) };
        bytes
    }

    fn data(&self) -> &[u8] {
        let t = self.get();
        assert!(!t.pData.is_null());
        unsafe { std::slice::from_raw_parts(t.pData, t.dataSize) }
    }
}

impl Drop for Texture {
    fn drop(&mut self) {
        unsafe {
            let destroy = (*(*self.0).vtbl).Destroy.unwrap();
            destroy(self.0 as *mut sys::ktxTexture);
        }
    }
}

extern "C" {
    /// C `free`, for the buffer `WriteToMemory` mallocs.
    #[link_name = "free"]
    fn libc_free(p: *mut std::os::raw::c_void);
}

fn error(rc: sys::ktx_error_code_e) -> String {
    unsafe { CStr::from_ptr(sys::ktxErrorString(rc)) }
        .to_string_lossy()
        .into_owned()
}

/// Khronos' `ktx2check`, built by `libktx-rs-sys`'s CMake build next to the library.
fn ktx2check() -> PathBuf {
    // the test executable is target/<profile>/deps/<name>; the build scripts' outputs are in
    // target/<profile>/build/libktx-rs-sys-<hash>/out
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(Path::parent).unwrap();
    let mut found: Vec<(std::time::SystemTime, PathBuf)> = Vec::new();
    for entry in std::fs::read_dir(profile_dir.join("build"))
        .unwrap()
        .flatten()
    {
        if !entry
            .file_name()
            .to_string_lossy()
            .starts_with("libktx-rs-sys-")
        {
            continue;
        }
        for candidate in ["out/bin/ktx2check", "out/build/tools/ktx2check/ktx2check"] {
            let candidate = entry.path().join(candidate);
            if let Ok(meta) = std::fs::metadata(&candidate) {
                found.push((meta.modified().unwrap(), candidate));
            }
        }
    }
    found.sort();
    found
        .pop()
        .unwrap_or_else(|| {
            panic!(
                "ktx2check was not found under {}/build/libktx-rs-sys-*/out/ \
                 (it is built with libktx by the libktx-rs-sys dev-dependency)",
                profile_dir.display()
            )
        })
        .1
}

/// The one complaint of ktx2check 4.0.0 that is a defect of that version, not of the file:
/// it expects the file to end with padding after the last (largest) level, as if
/// `align(lcm(texel size, 4))` followed every level. The specification puts `mipPadding`
/// before each level only, libktx 4.0.0's own writer writes no padding at the end, and
/// ktx2check rejects libktx's own output the same way (see
/// `ktx2check_quirk_also_rejects_libktx_own_output`); the later `ktx validate` dropped the check.
const KTX2CHECK_TRAILING_PADDING_QUIRK: &str =
    "Size of image data in file does not match size calculated from";

/// ktx2check 4.0.0's rule for supercompressed files that the specification has since
/// dropped: KTX 2.0 as first published set a supercompressed texture's `bytesPlane0` to 0;
/// the Data Format specification's issue 27 (KhronosGroup/DataFormat) concluded that the
/// bytes per plane must keep the uncompressed format's value, which the current specification
/// says, and later libktx reads a 0 there as "the deprecated way", reconstructing the value.
/// brdfbake writes the current form (the DFD of the plain file); libktx 4.0.0 itself loads
/// and inflates it (asserted in the test).
const KTX2CHECK_ZSTD_BYTES_PLANE_QUIRK: &str =
    "DFD bytes/plane must be 0 for a supercompressed texture";

/// Runs `ktx2check --warn-as-error`: `Ok` if it accepts the file, else its report.
fn ktx2check_report(bytes: &[u8]) -> Result<(), String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("table.ktx2");
    std::fs::write(&path, bytes).unwrap();
    let out = Command::new(ktx2check())
        .arg("--warn-as-error")
        .arg(&path)
        .output()
        .unwrap();
    if out.status.success() {
        return Ok(());
    }
    Err(format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ))
}

/// ktx2check accepts the file; the only tolerated complaint is the trailing-padding quirk,
/// and only when the level's length is not a multiple of the level alignment.
fn run_ktx2check(bytes: &[u8], level_length: usize, alignment: usize, what: &str) {
    let Err(report) = ktx2check_report(bytes) else {
        return;
    };
    let issues: Vec<&str> = report
        .lines()
        .filter(|l| l.contains("ERROR") || l.contains("WARNING") || l.contains("FATAL"))
        .collect();
    let quirk_only = issues.len() == 1 && issues[0].contains(KTX2CHECK_TRAILING_PADDING_QUIRK);
    assert!(
        quirk_only && !level_length.is_multiple_of(alignment),
        "{what}: ktx2check rejected the file:\n{report}"
    );
}

/// Everything libktx, the `ktx2` crate and ktx2check can tell about an encoded table.
fn check(lut: &Lut, enc: &Ktx2Encoder, bytes: &[u8]) {
    let what = format!(
        "{}D table, {} channels, {:?}{}",
        lut.axes.len(),
        lut.channels.len(),
        enc.storage,
        if enc.array_3d { ", array" } else { "" }
    );
    let nc = lut.channels.len();
    let components = if nc == 3 { 4 } else { nc };
    let component_bytes = match enc.storage {
        Storage::Unorm8 => 1,
        Storage::F16 | Storage::Unorm16 => 2,
        Storage::F32 => 4,
    };
    let vk_format = match (components, enc.storage) {
        (1, Storage::F16) => 76,     // VK_FORMAT_R16_SFLOAT
        (2, Storage::F16) => 83,     // VK_FORMAT_R16G16_SFLOAT
        (4, Storage::F16) => 97,     // VK_FORMAT_R16G16B16A16_SFLOAT
        (1, Storage::F32) => 100,    // VK_FORMAT_R32_SFLOAT
        (2, Storage::F32) => 103,    // VK_FORMAT_R32G32_SFLOAT
        (4, Storage::F32) => 109,    // VK_FORMAT_R32G32B32A32_SFLOAT
        (1, Storage::Unorm8) => 9,   // VK_FORMAT_R8_UNORM
        (2, Storage::Unorm8) => 16,  // VK_FORMAT_R8G8_UNORM
        (4, Storage::Unorm8) => 37,  // VK_FORMAT_R8G8B8A8_UNORM
        (1, Storage::Unorm16) => 70, // VK_FORMAT_R16_UNORM
        (2, Storage::Unorm16) => 77, // VK_FORMAT_R16G16_UNORM
        (4, Storage::Unorm16) => 91, // VK_FORMAT_R16G16B16A16_UNORM
        _ => unreachable!(),
    };
    let (nx, ny, nz) = (lut.dim(0), lut.dim(1), lut.dim(2));
    let is_3d = lut.axes.len() == 3 && !enc.array_3d;
    let is_array = lut.axes.len() == 3 && enc.array_3d;
    let orientation: &[u8] = if is_3d { b"rdi\0" } else { b"rd\0" };

    // --- libktx ---
    let tex = Texture::from_memory(bytes);
    let t = tex.get();
    assert_eq!(t.vkFormat, vk_format, "{what}");
    assert_eq!(
        (t.baseWidth, t.baseHeight, t.baseDepth),
        (nx as u32, ny as u32, if is_3d { nz as u32 } else { 1 }),
        "{what}"
    );
    assert_eq!(t.numDimensions, if is_3d { 3 } else { 2 }, "{what}");
    assert_eq!(t.isArray, is_array, "{what}");
    assert_eq!(t.numLayers, if is_array { nz as u32 } else { 1 }, "{what}");
    assert_eq!((t.numLevels, t.numFaces), (1, 1), "{what}");
    assert!(
        !t.isCubemap && !t.isCompressed && !t.generateMipmaps,
        "{what}"
    );
    assert_eq!(t.supercompressionScheme, 0, "{what}");
    assert_eq!(t.orientation.x, sys::ktxOrientationX_KTX_ORIENT_X_RIGHT);
    assert_eq!(t.orientation.y, sys::ktxOrientationY_KTX_ORIENT_Y_DOWN);
    if is_3d {
        assert_eq!(t.orientation.z, sys::ktxOrientationZ_KTX_ORIENT_Z_IN);
    }

    // the DFD is the one libktx makes for this vkFormat, and libktx reads it back as such
    assert_eq!(tex.dfd(), Texture::create(vk_format).dfd(), "{what}: DFD");
    let (mut n, mut size) = (0, 0);
    unsafe { sys::ktxTexture2_GetComponentInfo(tex.0, &mut n, &mut size) };
    assert_eq!((n as usize, size as usize), (components, component_bytes));
    assert_eq!(unsafe { sys::ktxTexture2_GetOETF(tex.0) }, 1, "linear");
    assert!(!unsafe { sys::ktxTexture2_GetPremultipliedAlpha(tex.0) });
    let element = unsafe { sys::ktxTexture_GetElementSize(tex.0 as *mut sys::ktxTexture) };
    assert_eq!(element as usize, components * component_bytes);

    // key/value data
    assert_eq!(tex.keys(), ["KTXorientation", "KTXwriter"], "{what}");
    assert_eq!(tex.value("KTXorientation").unwrap(), orientation, "{what}");
    let mut writer = WRITER.as_bytes().to_vec();
    writer.push(0);
    assert_eq!(tex.value("KTXwriter").unwrap(), writer, "{what}");
    assert!(WRITER.starts_with("brdfbake "));

    // every texel, where libktx says it is
    let data = tex.data();
    assert_eq!(
        data.len(),
        nx * ny * nz * components * component_bytes,
        "{what}"
    );
    // (not ktxTexture_GetRowPitch: libktx 4.0 pads that to GL_UNPACK_ALIGNMENT even for KTX2,
    // whose rows are tightly packed)
    let image_size = tex.image_size();
    assert_eq!(image_size, nx * ny * components * component_bytes, "{what}");
    let pitch = image_size / ny;
    for z in 0..nz {
        let image = if is_array {
            tex.image_offset(z as u32, 0)
        } else {
            tex.image_offset(0, z as u32)
        };
        for y in 0..ny {
            for x in 0..nx {
                for c in 0..components {
                    let v = if c < nc { lut.texel([x, y, z], c) } else { 1.0 };
                    let want = match enc.storage {
                        Storage::F32 => v.to_le_bytes().to_vec(),
                        Storage::F16 => f16::from_f32(v).to_le_bytes().to_vec(),
                        Storage::Unorm8 => vec![unorm_code(v, 255) as u8],
                        Storage::Unorm16 => unorm_code(v, 65535).to_le_bytes().to_vec(),
                    };
                    let at = image + y * pitch + (x * components + c) * component_bytes;
                    assert_eq!(
                        &data[at..at + component_bytes],
                        &want[..],
                        "{what}: texel [{x}, {y}, {z}] component {c}"
                    );
                }
            }
        }
    }
    drop(tex);

    // --- the ktx2 crate ---
    let reader = ktx2::Reader::new(bytes).unwrap_or_else(|e| panic!("{what}: ktx2: {e:?}"));
    let h = reader.header();
    assert_eq!(h.format.map(|f| f.value()), Some(vk_format));
    assert_eq!(h.type_size as usize, component_bytes);
    assert_eq!(
        (h.pixel_width, h.pixel_height, h.pixel_depth, h.layer_count),
        (
            nx as u32,
            ny as u32,
            if is_3d { nz as u32 } else { 0 },
            if is_array { nz as u32 } else { 0 }
        ),
        "{what}"
    );
    assert_eq!((h.face_count, h.level_count), (1, 1));
    assert!(h.supercompression_scheme.is_none());
    assert_eq!((h.index.sgd_byte_offset, h.index.sgd_byte_length), (0, 0));
    assert_eq!(h.index.dfd_byte_offset, 80 + 24);
    assert_eq!(
        h.index.kvd_byte_offset,
        h.index.dfd_byte_offset + h.index.dfd_byte_length
    );
    assert_eq!(h.index.kvd_byte_length % 4, 0);
    let basic = reader.basic_dfd().expect("a basic DFD block");
    let (want_basic, _) = ktx2::dfd::Basic::from_format(h.format.unwrap()).unwrap();
    assert_eq!(basic, &want_basic, "{what}");
    assert_eq!(reader.color_model(), Some(ktx2::ColorModel::RGBSDA));
    assert_eq!(reader.color_primaries(), Some(ktx2::ColorPrimaries::BT709));
    assert_eq!(
        reader.transfer_function(),
        Some(ktx2::TransferFunction::Linear)
    );
    assert_eq!(reader.is_alpha_premultiplied(), Some(false));
    // the ktx2 crate returns the stored value, terminating NUL included
    assert_eq!(reader.writer(), Some(format!("{WRITER}\0").as_str()));
    let kvd: Vec<(&str, &[u8])> = reader.key_value_data().collect();
    assert_eq!(
        kvd,
        [
            ("KTXorientation", orientation),
            ("KTXwriter", writer.as_slice())
        ]
    );
    let levels: Vec<ktx2::Level> = reader.levels().collect();
    assert_eq!(levels.len(), 1);
    assert_eq!(
        levels[0].uncompressed_byte_length,
        levels[0].data.len() as u64
    );
    let level_offset = levels[0].data.as_ptr() as usize - bytes.as_ptr() as usize;
    let texel = components * component_bytes;
    let alignment = if texel % 4 == 0 { texel } else { 4 };
    assert_eq!(level_offset % alignment, 0, "{what}: level alignment");
    assert_eq!(level_offset + levels[0].data.len(), bytes.len(), "{what}");
    // only zero padding between the key/value data and the level
    let kvd_end = (h.index.kvd_byte_offset + h.index.kvd_byte_length) as usize;
    assert!(bytes[kvd_end..level_offset].iter().all(|&b| b == 0));
    assert_eq!(levels[0].data, Texture::from_memory(bytes).data(), "{what}");

    // --- libktx's own writer lays the same texture out the same way ---
    let rewritten = Texture::from_memory(bytes).write_to_memory();
    let r = ktx2::Reader::new(&rewritten[..]).unwrap();
    let rh = r.header();
    assert_eq!(
        (
            rh.format,
            rh.type_size,
            rh.pixel_width,
            rh.pixel_height,
            rh.pixel_depth
        ),
        (
            h.format,
            h.type_size,
            h.pixel_width,
            h.pixel_height,
            h.pixel_depth
        )
    );
    assert_eq!(
        (rh.layer_count, rh.face_count, rh.level_count),
        (h.layer_count, h.face_count, h.level_count)
    );
    assert_eq!(rh.supercompression_scheme, h.supercompression_scheme);
    let (i, ri) = (h.index, rh.index);
    assert_eq!(
        (ri.dfd_byte_offset, ri.dfd_byte_length, ri.kvd_byte_offset),
        (i.dfd_byte_offset, i.dfd_byte_length, i.kvd_byte_offset),
        "{what}"
    );
    assert_eq!((ri.sgd_byte_offset, ri.sgd_byte_length), (0, 0));
    let dfd_range = |i: ktx2::Index| {
        i.dfd_byte_offset as usize..(i.dfd_byte_offset + i.dfd_byte_length) as usize
    };
    assert_eq!(&rewritten[dfd_range(ri)], &bytes[dfd_range(i)], "{what}");
    // libktx appends " / libktx <version>" to KTXwriter, nothing else changes in the KVD
    let rkvd: Vec<(&str, &[u8])> = r.key_value_data().collect();
    assert_eq!(rkvd.len(), 2);
    assert_eq!(rkvd[0], ("KTXorientation", orientation));
    assert_eq!(rkvd[1].0, "KTXwriter");
    assert!(rkvd[1].1.starts_with(WRITER.as_bytes()), "{what}");
    let rlevels: Vec<ktx2::Level> = r.levels().collect();
    assert_eq!(rlevels.len(), 1);
    assert_eq!(rlevels[0].data, levels[0].data, "{what}");
    let rlevel_offset = rlevels[0].data.as_ptr() as usize - rewritten.as_ptr() as usize;
    let rkvd_end = (ri.kvd_byte_offset + ri.kvd_byte_length) as usize;
    assert_eq!(
        rlevel_offset,
        rkvd_end.next_multiple_of(alignment),
        "{what}"
    );
    assert_eq!(level_offset, kvd_end.next_multiple_of(alignment), "{what}");
    assert_eq!(
        rewritten.len(),
        rlevel_offset + rlevels[0].data.len(),
        "{what}"
    );

    // --- Khronos' validator ---
    run_ktx2check(bytes, levels[0].data.len(), alignment, &what);
}

fn encode_and_check(lut: &Lut, enc: &Ktx2Encoder) -> Vec<u8> {
    let bytes = enc.encode(lut, &[]).unwrap();
    check(lut, enc, &bytes);
    bytes
}

#[test]
fn tables_2d_all_channel_counts_and_storages() {
    for storage in Storage::ALL {
        for nc in 1..=4 {
            // odd, non-square sizes: rows of every length modulo 4 bytes
            let t = lut(&[5 + nc, 3], nc, values_for(storage));
            encode_and_check(&t, &encoder(storage, false));
        }
    }
}

#[test]
fn table_1d_is_a_2d_texture_of_height_1() {
    for storage in Storage::ALL {
        let t = lut(&[9], 1, values_for(storage));
        let bytes = encode_and_check(&t, &encoder(storage, false));
        assert_eq!(ktx2::Reader::new(&bytes).unwrap().header().pixel_height, 1);
    }
}

#[test]
fn table_3d_as_3d_texture_and_as_array() {
    for storage in Storage::ALL {
        for array_3d in [false, true] {
            for nc in [1, 3] {
                let t = lut(&[4, 3, 5], nc, values_for(storage));
                encode_and_check(&t, &encoder(storage, array_3d));
            }
        }
    }
    // array_3d changes nothing for tables with fewer axes
    let t = lut(&[4, 3], 2, value);
    assert_eq!(
        encoder(Storage::F16, true).encode(&t, &[]).unwrap(),
        encoder(Storage::F16, false).encode(&t, &[]).unwrap()
    );
}

/// Zstandard supercompression (`supercompressionScheme` 2, the `ktx2-zstd` format): libktx
/// loads the file and inflates its level to exactly the bytes it loads from the plain file of
/// the same table, with the same vkFormat, sizes, layers, DFD and key/value data; the `ktx2`
/// crate sees the scheme and the inflated length in the level index; ktx2check accepts it.
#[test]
fn zstd_supercompressed_tables_inflate_to_the_plain_texels() {
    let shapes: [(&[usize], usize, bool); 6] = [
        (&[9], 1, false),
        (&[7, 3], 2, false),
        (&[5, 4], 3, false),
        (&[6, 5], 4, false),
        (&[4, 3, 5], 2, false),
        (&[4, 3, 5], 4, true),
    ];
    for storage in Storage::ALL {
        for (sizes, nc, array_3d) in shapes {
            let what = format!("{sizes:?}, {nc} channels, {storage:?}, array {array_3d}");
            let t = lut(sizes, nc, values_for(storage));
            let plain_encoder = encoder(storage, array_3d);
            let plain = plain_encoder.encode(&t, &[]).unwrap();
            let zstd_encoder = Ktx2Encoder {
                supercompression: Supercompression::Zstd,
                ..plain_encoder
            };
            let z = zstd_encoder.encode(&t, &[]).unwrap();
            assert_eq!(
                z,
                zstd_encoder.encode(&t, &[]).unwrap(),
                "{what}: deterministic"
            );

            let r = ktx2::Reader::new(&z[..]).unwrap();
            assert_eq!(
                r.header().supercompression_scheme,
                Some(ktx2::SupercompressionScheme::Zstandard),
                "{what}"
            );
            let plain_level = ktx2::Reader::new(&plain[..])
                .unwrap()
                .levels()
                .next()
                .unwrap()
                .data
                .len();
            let level = r.levels().next().unwrap();
            assert_eq!(
                level.uncompressed_byte_length as usize, plain_level,
                "{what}"
            );

            let (zt, pt) = (Texture::from_memory(&z), Texture::from_memory(&plain));
            let (a, b) = (zt.get(), pt.get());
            assert_eq!(
                (
                    a.vkFormat,
                    a.baseWidth,
                    a.baseHeight,
                    a.baseDepth,
                    a.numLayers,
                    a.isArray
                ),
                (
                    b.vkFormat,
                    b.baseWidth,
                    b.baseHeight,
                    b.baseDepth,
                    b.numLayers,
                    b.isArray
                ),
                "{what}"
            );
            assert_eq!(zt.dfd(), pt.dfd(), "{what}: DFD");
            assert_eq!(zt.keys(), pt.keys(), "{what}");
            assert_eq!(zt.data(), pt.data(), "{what}: the inflated texels");
            if let Err(report) = ktx2check_report(&z) {
                let issues: Vec<&str> = report
                    .lines()
                    .filter(|l| l.contains("ERROR") || l.contains("WARNING") || l.contains("FATAL"))
                    .collect();
                assert!(
                    issues.len() == 1 && issues[0].contains(KTX2CHECK_ZSTD_BYTES_PLANE_QUIRK),
                    "{what}: ktx2check rejected the file:\n{report}"
                );
            }
        }
    }
}

#[test]
fn f16_overflow_is_an_error() {
    // 65519 rounds to 65504; 65520 rounds to infinity
    let t = lut(&[3, 2], 2, |p, c| {
        if c == 1 && p == [2, 1, 0] {
            -65520.0
        } else {
            65519.0
        }
    });
    match encoder(Storage::F16, false).encode(&t, &[]) {
        Err(EncodeError::Unrepresentable {
            table,
            channel,
            value,
            ..
        }) => {
            assert_eq!(table, "test-table");
            assert_eq!(channel, "A");
            assert_eq!(value, -65520.0);
        }
        other => panic!("expected Unrepresentable, got {other:?}"),
    }
    // f32 holds it
    encode_and_check(&t, &encoder(Storage::F32, false));
    // and f16 holds the largest value that rounds to a finite half
    let ok = lut(&[3, 2], 2, |_, _| -65519.0);
    encode_and_check(&ok, &encoder(Storage::F16, false));
}

/// A UNORM value more than half a step outside [0, 1] is an error naming the table, the
/// channel, the texel and the value: never clamped. Within half a step it rounds to the end
/// code (checked by the tables above, whose values include 1 + 1e-6 and -1e-6).
#[test]
fn unorm_out_of_range_is_an_error() {
    for storage in [Storage::Unorm8, Storage::Unorm16] {
        let max = storage.unorm_max().unwrap() as f32;
        for bad in [1.0 + 0.51 / max, -0.51 / max, 2.0, -1.0] {
            let t = lut(&[4, 3], 2, |p, c| {
                if c == 1 && p == [3, 2, 0] {
                    bad
                } else {
                    0.25
                }
            });
            match encoder(storage, false).encode(&t, &[]) {
                Err(EncodeError::OutOfUnitRange {
                    table,
                    channel,
                    texel,
                    value,
                    ..
                }) => {
                    assert_eq!(table, "test-table");
                    assert_eq!(channel, "A");
                    assert_eq!(texel, [3, 2]);
                    assert_eq!(value, bad as f64);
                }
                other => panic!("{storage:?} {bad}: expected OutOfUnitRange, got {other:?}"),
            }
        }
    }
}

#[test]
fn nan_is_an_error() {
    for storage in Storage::ALL {
        let t = lut(&[4, 3, 2], 3, |p, c| {
            if p == [1, 2, 1] && c == 2 {
                f32::NAN
            } else {
                0.5
            }
        });
        match encoder(storage, false).encode(&t, &[]) {
            Err(EncodeError::NonFinite { channel, texel, .. }) => {
                assert_eq!(channel, "B");
                assert_eq!(texel, [1, 2, 1]);
            }
            other => panic!("expected NonFinite, got {other:?}"),
        }
    }
}

#[test]
fn shape_errors() {
    let five = lut(&[2, 2], 4, value);
    let mut five = five.clone();
    five.channels.push(Channel {
        name: "extra".into(),
        meaning: String::new(),
    });
    five.data = vec![0.0; 2 * 2 * 5];
    assert!(matches!(
        encoder(Storage::F32, false).encode(&five, &[]),
        Err(EncodeError::Shape { .. })
    ));
    let mut short = lut(&[2, 2], 1, value);
    short.data.pop();
    assert!(matches!(
        encoder(Storage::F32, false).encode(&short, &[]),
        Err(EncodeError::Shape { .. })
    ));
}

#[test]
fn deterministic_and_attributes_are_ignored() {
    for storage in Storage::ALL {
        let t = lut(&[6, 4, 3], 3, values_for(storage));
        let enc = encoder(storage, false);
        let a = enc.encode(&t, &[]).unwrap();
        let b = enc.encode(&t.clone(), &[]).unwrap();
        assert_eq!(a, b);
        let attributes = vec![("preset".to_string(), "unit-test".to_string())];
        assert_eq!(enc.encode(&t, &attributes).unwrap(), a);
        assert_eq!(enc.extension(), "ktx2");
    }
}

/// The ktx2check 4.0.0 defect tolerated above: libktx 4.0.0 writes a 9×1 R16_SFLOAT texture
/// (18 bytes of level data, level alignment 4) with no padding after the level, exactly as
/// brdfbake does, and ktx2check rejects libktx's own file with that one complaint.
#[test]
fn ktx2check_quirk_also_rejects_libktx_own_output() {
    let mut info = sys::ktxTextureCreateInfo {
        glInternalformat: 0,
        vkFormat: 76, // VK_FORMAT_R16_SFLOAT
        pDfd: ptr::null_mut(),
        baseWidth: 9,
        baseHeight: 1,
        baseDepth: 1,
        numDimensions: 2,
        numLevels: 1,
        numLayers: 1,
        numFaces: 1,
        isArray: false,
        generateMipmaps: false,
    };
    let mut tex: *mut sys::ktxTexture2 = ptr::null_mut();
    let rc = unsafe {
        sys::ktxTexture2_Create(
            &mut info,
            sys::ktxTextureCreateStorageEnum_KTX_TEXTURE_CREATE_ALLOC_STORAGE,
            &mut tex,
        )
    };
    assert_eq!(rc, sys::ktx_error_code_e_KTX_SUCCESS);
    let tex = Texture(tex);
    let image = [0x3c_u8; 18];
    let rc = unsafe {
        let set = (*tex.get().vtbl).SetImageFromMemory.unwrap();
        set(
            tex.0 as *mut sys::ktxTexture,
            0,
            0,
            0,
            image.as_ptr(),
            image.len(),
        )
    };
    assert_eq!(rc, sys::ktx_error_code_e_KTX_SUCCESS);
    let bytes = tex.write_to_memory();
    let reader = ktx2::Reader::new(&bytes[..]).unwrap();
    let level = reader.levels().next().unwrap();
    assert_eq!(level.data.len(), 18);
    assert_eq!(
        level.data.as_ptr() as usize - bytes.as_ptr() as usize + 18,
        bytes.len(),
        "libktx writes no padding after the last level"
    );
    let report = ktx2check_report(&bytes).expect_err("ktx2check 4.0.0 rejects this file");
    assert!(
        report.contains(KTX2CHECK_TRAILING_PADDING_QUIRK),
        "{report}"
    );
}

/// Negative controls: the checkers used above do reject broken files. A vkFormat that
/// disagrees with the DFD fails ktx2check; an array texture labelled with a 3-character
/// orientation (`rdi`: the KTX orientation has no character for the array dimension) fails
/// to load in libktx.
#[test]
fn checkers_reject_broken_files() {
    let t = lut(&[4, 3, 5], 1, value);
    let mut bytes = encoder(Storage::F16, false).encode(&t, &[]).unwrap();
    assert!(ktx2check_report(&bytes).is_ok());
    let mut wrong_format = bytes.clone();
    wrong_format[12..16].copy_from_slice(&100u32.to_le_bytes()); // R32_SFLOAT
    assert!(ktx2check_report(&wrong_format).is_err());

    // the 3D texture (orientation "rdi") relabelled as a 5-layer array texture
    bytes[28..32].copy_from_slice(&0u32.to_le_bytes()); // pixelDepth
    bytes[32..36].copy_from_slice(&5u32.to_le_bytes()); // layerCount
    let mut tex: *mut sys::ktxTexture2 = ptr::null_mut();
    let rc = unsafe {
        sys::ktxTexture2_CreateFromMemory(
            bytes.as_ptr(),
            bytes.len(),
            sys::ktxTextureCreateFlagBits_KTX_TEXTURE_CREATE_LOAD_IMAGE_DATA_BIT,
            &mut tex,
        )
    };
    assert_eq!(rc, sys::ktx_error_code_e_KTX_FILE_DATA_ERROR);
    assert!(ktx2check_report(&bytes).is_err());
}
