//! Reading back what brdfbake wrote: a texture (EXR, KTX2 or png-data PNG) and/or its JSON
//! sidecar (`brdfbake.lut/1`) become a [`Lut`] plus the table specification the sidecar
//! describes, rebuilt exactly (its input hash is recomputed and compared). Normalized-integer
//! texels (UNORM8, UNORM16) read back as what a sampler returns, `code/(2ⁿ − 1)`.
//!
//! Files brdfbake did not write are rejected with [`ReadError::Input`]: an EXR needs our
//! `brdfbake:schema` header attribute, a KTX2 our `KTXwriter`, a PNG our `brdfbake:schema`
//! text chunk and the png-data note (a preview is refused as one), a JSON file our schema.

use crate::encode::exr::{decode_exr, ATTRIBUTE_PREFIX};
use crate::lut::{Axis, Channel, Convention, Lut, Quantity};
use crate::meta;
use crate::model::RoughnessQuantity;
use crate::preset::PresetTable;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};

/// Largest file read back (textures of at most 2^24 texels × 4 channels × 4 bytes, plus room).
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Why a file could not be read back.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file is not something brdfbake wrote, or is inconsistent (exit code 2).
    #[error("{0}")]
    Input(String),
    /// The file exists but cannot be read (exit code 1).
    #[error("{0}")]
    Io(String),
}

/// A texture and/or sidecar read back.
#[derive(Debug, Clone)]
pub struct Readback {
    /// The texture file, if one was found.
    pub texture: Option<PathBuf>,
    /// `exr`, `ktx2` or `png-data` when a texture was read.
    pub texture_format: Option<&'static str>,
    /// The sidecar's path, if one was found.
    pub sidecar_path: Option<PathBuf>,
    /// The sidecar's JSON.
    pub sidecar: Option<Value>,
    /// The table the sidecar describes, rebuilt (validated) from it.
    pub table: Option<PresetTable>,
    /// The preset name recorded in the sidecar (or the EXR header).
    pub preset: Option<String>,
    /// Whether the rebuilt table's input hash equals the sidecar's (`None`: no sidecar).
    pub hash_matches: Option<bool>,
    /// What the texture itself says: EXR `brdfbake:` attributes (prefix removed), KTX2
    /// header facts.
    pub file_facts: Vec<(String, String)>,
    /// The stored texels (stored = value × scale) with the sidecar's axes, or, without a
    /// sidecar, the axes the file itself tells (generic `x`, `y` when it tells none).
    pub lut: Option<Lut>,
    /// Stored value = value × scale.
    pub scale: f64,
}

/// Reads a regular file of at most [`MAX_FILE_BYTES`] (a FIFO, device or directory is an
/// input error, never opened, so it cannot block or stream forever).
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, ReadError> {
    crate::input::read_regular(
        path,
        MAX_FILE_BYTES,
        "a .exr, .ktx2, png-data .png or .json file brdfbake wrote",
    )
    .map_err(|e| match e {
        crate::input::InputError::Input(m) => ReadError::Input(m),
        crate::input::InputError::Io(m) => ReadError::Io(m),
    })
}

fn ext_of(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Reads `path` (`.exr`, `.ktx2` or the `.json` sidecar) and whatever of the pair lies next
/// to it.
pub fn read(path: &Path) -> Result<Readback, ReadError> {
    let ext = ext_of(path);
    let (texture, sidecar_path) = match ext.as_str() {
        "exr" | "ktx2" | "dds" | "png" => {
            let j = path.with_extension("json");
            (Some(path.to_path_buf()), sidecar_beside(&j)?)
        }
        "json" => (None, Some(path.to_path_buf())),
        _ => {
            return Err(ReadError::Input(format!(
                "{}: not a file brdfbake reads back (accepted: .exr, .ktx2, .dds, a png-data .png, or the .json sidecar)",
                path.display()
            )))
        }
    };
    let mut rb = Readback {
        texture: None,
        texture_format: None,
        sidecar_path: None,
        sidecar: None,
        table: None,
        preset: None,
        hash_matches: None,
        file_facts: Vec::new(),
        lut: None,
        scale: 1.0,
    };
    if let Some(sp) = &sidecar_path {
        let bytes = read_bytes(sp)?;
        let sealed = crate::digest::check_seal(&bytes);
        let v: Value = serde_json::from_slice(&bytes).map_err(|e| {
            ReadError::Input(format!(
                "{}: not a brdfbake sidecar: invalid JSON ({e})",
                sp.display()
            ))
        })?;
        if v.get("schema").and_then(Value::as_str) == Some(crate::preset::SCHEMA) {
            return Err(ReadError::Input(format!(
                "{}: is a preset ({}), not the sidecar of a baked table: bake it, or give it to `brdfbake verify`",
                sp.display(),
                crate::preset::SCHEMA
            )));
        }
        if v.get("schema").and_then(Value::as_str) != Some(meta::SCHEMA) {
            return Err(ReadError::Input(format!(
                "{}: not a brdfbake sidecar: \"schema\" must be {:?}",
                sp.display(),
                meta::SCHEMA
            )));
        }
        sealed.map_err(|e| ReadError::Input(format!("{}: {e}", sp.display())))?;
        // `measured --out` tables have no preset table to rebuild (nor an input hash)
        let measured =
            v.pointer("/table/kind").and_then(Value::as_str) == Some(meta::MEASURED_TABLE_KIND);
        if !measured {
            let table = table_from_sidecar(&v)
                .map_err(|e| ReadError::Input(format!("{}: {e}", sp.display())))?;
            // the sidecar agrees with itself: its axes (coordinates, α) and channels are what
            // this version writes for the table it describes
            let (axes, channels) = meta::axes_and_channels(&table);
            for (key, want) in [("axes", axes), ("channels", channels)] {
                let have = v.get(key).cloned().unwrap_or(Value::Null);
                if let Some(at) = json_difference(&have, &want, key) {
                    return Err(ReadError::Input(format!(
                        "{}: {at} disagrees with the table the sidecar describes (recomputed from its axes' formulas and channels): the sidecar was edited",
                        sp.display()
                    )));
                }
            }
            rb.hash_matches = Some(
                v.get("input_hash").and_then(Value::as_str) == Some(&meta::input_hash(&table)),
            );
            rb.preset = v.get("preset").and_then(Value::as_str).map(String::from);
            rb.scale = table.scale;
            rb.table = Some(table);
        }
        rb.sidecar = Some(v);
        rb.sidecar_path = Some(sp.clone());
    }
    // a sidecar given directly: find its texture through its `files`
    let texture = match texture {
        Some(t) => Some(t),
        None => {
            let files = rb.sidecar.as_ref().and_then(|v| v.get("files"));
            ["exr", "ktx2", "dds", "png"].iter().find_map(|k| {
                let name = files?.get(*k)?.as_str()?;
                let p = path.with_file_name(name);
                p.is_file().then_some(p)
            })
        }
    };
    if let Some(t) = texture {
        let bytes = read_bytes(&t)?;
        if let Some(v) = &rb.sidecar {
            let name = t.file_name().map(|n| n.to_string_lossy().into_owned());
            crate::digest::check_file(v, name.as_deref().unwrap_or(""), &bytes).map_err(|e| {
                ReadError::Input(format!(
                    "{}: {e} (sidecar {})",
                    t.display(),
                    rb.sidecar_path
                        .as_ref()
                        .map_or(String::new(), |p| p.display().to_string())
                ))
            })?;
        }
        let ext = ext_of(&t);
        let (lut, facts) = match ext.as_str() {
            "exr" => read_exr(&t, &bytes, rb.table.as_ref())?,
            "png" => read_png_data(&t, &bytes, rb.table.as_ref())?,
            "dds" => read_dds(&t, &bytes, rb.table.as_ref())?,
            _ => read_ktx2(&t, &bytes, rb.table.as_ref())?,
        };
        if rb.preset.is_none() {
            rb.preset = facts
                .iter()
                .find(|(k, _)| k == "preset")
                .map(|(_, v)| v.clone());
            if let Some(s) = facts.iter().find(|(k, _)| k == "scale") {
                rb.scale = s.1.parse().unwrap_or(1.0);
            }
        }
        if let (Some(v), Some((_, h))) =
            (&rb.sidecar, facts.iter().find(|(k, _)| k == "input_hash"))
        {
            let want = v.get("input_hash").and_then(Value::as_str).unwrap_or("");
            if h != want {
                return Err(ReadError::Input(format!(
                    "{}: its header's input hash {h} is not its sidecar's {want}: the texture was baked for another table",
                    t.display()
                )));
            }
        }
        // the header carries the input hash (EXR attribute, PNG text chunk) where the format
        // has a place for it: a sealed sidecar next to a texture without it is a mismatch
        if rb.table.is_some()
            && matches!(ext.as_str(), "exr" | "png")
            && !facts.iter().any(|(k, _)| k == "input_hash")
        {
            return Err(ReadError::Input(format!(
                "{}: its header has no input hash ({}), which every {} brdfbake writes holds and its sidecar's must equal",
                t.display(),
                if ext == "exr" { "attribute brdfbake:input_hash" } else { "text chunk input_hash" },
                if ext == "exr" { "EXR" } else { "png-data file" }
            )));
        }
        // a KTX2 or DDS file is exactly what this version writes for the table it holds: any
        // header, descriptor, key/value, index or trailing byte that differs is named
        if let Some(table) = &rb.table {
            if matches!(ext.as_str(), "ktx2" | "dds") {
                let writer = facts
                    .iter()
                    .find(|(k, _)| k == "writer")
                    .map(|(_, w)| w.as_str());
                structure_check(&t, &ext, &bytes, table, rb.sidecar.as_ref(), &lut, writer)?;
            }
        }
        rb.lut = Some(lut);
        rb.file_facts = facts;
        rb.texture_format = Some(match ext.as_str() {
            "exr" => "exr",
            "png" => "png-data",
            "dds" => "dds",
            _ => "ktx2",
        });
        rb.texture = Some(t);
    }
    Ok(rb)
}

/// Compares a KTX2 or DDS file with the bytes this version writes for the table it holds
/// (its texels, as read, encoded again with the sidecar's storage, 3D layout and KTX2
/// supercompression). A KTX2 file another brdfbake version wrote (its `KTXwriter`, the
/// `writer` fact of [`read_ktx2`]) is left to the checks of [`read_ktx2`].
fn structure_check(
    path: &Path,
    ext: &str,
    bytes: &[u8],
    table: &PresetTable,
    sidecar: Option<&Value>,
    lut: &Lut,
    writer: Option<&str>,
) -> Result<(), ReadError> {
    use crate::encode::Encoder;
    let array_3d = table.layout_3d == crate::preset::Layout3d::Array;
    let name = table.spec.name.clone();
    let want = if ext == "dds" {
        crate::encode::dds::DdsEncoder {
            storage: table.spec.storage,
            table_name: name,
            array_3d,
        }
        .encode(lut, &[])
    } else {
        // (the KTXwriter read_ktx2 found)
        if writer != Some(crate::encode::ktx2::WRITER) {
            return Ok(());
        }
        let zstd = sidecar
            .and_then(|v| v.pointer("/storage/ktx2/supercompression"))
            .and_then(Value::as_str)
            == Some("zstd");
        crate::encode::ktx2::Ktx2Encoder {
            storage: table.spec.storage,
            table_name: name,
            array_3d,
            supercompression: if zstd {
                crate::encode::ktx2::Supercompression::Zstd
            } else {
                crate::encode::ktx2::Supercompression::None
            },
        }
        .encode(lut, &[])
    };
    let want =
        want.map_err(|e| mismatch(path, format!("its texels cannot be written back: {e}")))?;
    if want == bytes {
        return Ok(());
    }
    let at = want
        .iter()
        .zip(bytes)
        .position(|(a, b)| a != b)
        .unwrap_or(want.len().min(bytes.len()));
    let field = if ext == "dds" {
        dds_field(at)
    } else {
        ktx2_field(&want, at)
    };
    Err(mismatch(
        path,
        if bytes.len() != want.len() && at == want.len().min(bytes.len()) {
            format!(
                "it is {} bytes, the table it holds is written in {} ({})",
                bytes.len(),
                want.len(),
                if bytes.len() > want.len() {
                    "bytes appended"
                } else {
                    "truncated"
                }
            )
        } else {
            format!(
                "byte {at} ({field}) differs from what brdfbake writes for this table and its sidecar"
            )
        },
    ))
}

/// The KTX2 field at byte `at` of a file laid out as `bytes` (this version's layout).
fn ktx2_field(bytes: &[u8], at: usize) -> String {
    const HEADER: [(usize, &str); 9] = [
        (12, "vkFormat"),
        (16, "typeSize"),
        (20, "pixelWidth"),
        (24, "pixelHeight"),
        (28, "pixelDepth"),
        (32, "layerCount"),
        (36, "faceCount"),
        (40, "levelCount"),
        (44, "supercompressionScheme"),
    ];
    if at < 12 {
        return "the identifier".into();
    }
    if let Some((_, n)) = HEADER.iter().find(|(o, _)| at >= *o && at < o + 4) {
        return format!("header field {n}");
    }
    if at < 80 {
        return "the index (DFD, key/value or supercompression data offsets and lengths)".into();
    }
    if at < 104 {
        return "the level index".into();
    }
    let u = |o: usize| u32::from_le_bytes(bytes[o..o + 4].try_into().expect("4 bytes")) as usize;
    let (dfd, kvd) = ((u(48), u(52)), (u(56), u(60)));
    if at >= dfd.0 && at < dfd.0 + dfd.1 {
        return "the Data Format Descriptor".into();
    }
    if at >= kvd.0 && at < kvd.0 + kvd.1 {
        return "the key/value data (KTXorientation, KTXwriter)".into();
    }
    "the level's texels or its padding".into()
}

/// The DDS field at byte `at` (the layout [`crate::encode::dds`] writes).
fn dds_field(at: usize) -> String {
    const FIELDS: [&str; 36] = [
        "dwSize",
        "dwFlags",
        "dwHeight",
        "dwWidth",
        "dwPitchOrLinearSize",
        "dwDepth",
        "dwMipMapCount",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "dwReserved1",
        "ddspf.dwSize",
        "ddspf.dwFlags",
        "ddspf.dwFourCC",
        "ddspf.dwRGBBitCount",
        "ddspf.dwRBitMask",
        "ddspf.dwGBitMask",
        "ddspf.dwBBitMask",
        "ddspf.dwABitMask",
        "dwCaps",
        "dwCaps2",
        "dwCaps3",
        "dwCaps4",
        "dwReserved2",
        "dxgiFormat",
        "resourceDimension",
        "miscFlag",
        "arraySize",
        "miscFlags2",
    ];
    if at < 4 {
        return "the magic".into();
    }
    FIELDS
        .get((at - 4) / 4)
        .map_or("the texels".into(), |f| format!("header field {f}"))
}

/// The first place where `have` differs from `want`, as a path (`axes[1].coordinates[3]`);
/// numbers equal when they print the same (a JSON round trip keeps f64s exactly).
fn json_difference(have: &Value, want: &Value, at: &str) -> Option<String> {
    match (have, want) {
        (Value::Object(a), Value::Object(b)) => {
            for (k, w) in b {
                if let Some(d) =
                    json_difference(a.get(k).unwrap_or(&Value::Null), w, &format!("{at}.{k}"))
                {
                    return Some(d);
                }
            }
            a.keys()
                .find(|k| !b.contains_key(*k))
                .map(|k| format!("{at}.{k} (not a field this version writes)"))
        }
        (Value::Array(a), Value::Array(b)) => {
            if a.len() != b.len() {
                return Some(format!(
                    "{at} ({} entries, the table has {})",
                    a.len(),
                    b.len()
                ));
            }
            a.iter()
                .zip(b)
                .enumerate()
                .find_map(|(i, (x, y))| json_difference(x, y, &format!("{at}[{i}]")))
        }
        (Value::Number(a), Value::Number(b)) => {
            (a.as_f64() != b.as_f64()).then(|| format!("{at} ({a}, the table's {b})"))
        }
        (a, b) => (a != b).then(|| format!("{at} ({a}, the table's {b})")),
    }
}

/// The sidecar at `j` beside a texture: `None` when nothing is there; an error when something
/// other than a readable regular file is (a FIFO, a device, a directory, a link that loops or
/// leads nowhere), which a reader must not open or silently skip.
fn sidecar_beside(j: &Path) -> Result<Option<PathBuf>, ReadError> {
    match std::fs::symlink_metadata(j) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(ReadError::Input(format!(
                "{}: the sidecar's path cannot be read: {e}",
                j.display()
            )))
        }
        Ok(_) => {}
    }
    match std::fs::metadata(j) {
        Ok(m) if m.is_file() => Ok(Some(j.to_path_buf())),
        Ok(m) => Err(ReadError::Input(format!(
            "{}: the sidecar's path holds {}, not a file: move it away, or put the table's sidecar there",
            j.display(),
            crate::input::kind_of(&m.file_type())
        ))),
        Err(e) => Err(ReadError::Input(format!(
            "{}: the sidecar's path is a link that loops or leads nowhere ({e})",
            j.display()
        ))),
    }
}

/// Rebuilds the table a sidecar describes by turning it back into a preset table and
/// validating that like any preset.
pub fn table_from_sidecar(v: &Value) -> Result<PresetTable, String> {
    let get = |path: &[&str]| -> Option<&Value> {
        let mut x = v;
        for p in path {
            x = x.get(*p)?;
        }
        Some(x)
    };
    let need = |path: &[&str]| -> Result<&Value, String> {
        get(path).ok_or_else(|| format!("the sidecar lacks {}", path.join(".")))
    };
    let name = need(&["table", "name"])?.clone();
    let kind = need(&["table", "kind"])?.clone();
    let mut model = Map::new();
    if let Some(n) = get(&["model", "ndf", "name"]) {
        model.insert("ndf".into(), n.clone());
    }
    if let Some(c) = get(&["model", "classic", "parameters"]) {
        // a classic table: the classic model is the model, there is no masking term
        model.insert("classic".into(), c.clone());
    } else {
        model.insert(
            "masking".into(),
            need(&["model", "masking", "name"])?.clone(),
        );
    }
    if let Some(f) = get(&["model", "fresnel", "parameters"]) {
        model.insert("fresnel".into(), f.clone());
    }
    if let Some(d) = get(&["model", "diffuse", "weight"]) {
        model.insert("diffuse".into(), d.clone());
    }
    // the diffuse lobe's model where it is not Lambert's (the preset's default), as the sidecar
    // names it (Burley's: an ltc table's lobe)
    if let Some(n) = get(&["model", "diffuse", "name"]).and_then(Value::as_str) {
        if n != "none" && n != crate::model::DiffuseModel::Lambert.name() {
            model.insert("diffuse_model".into(), Value::from(n));
        }
    }
    let mut axes = Map::new();
    // the stored order (the preset's axis_order, which the kind's own order leaves unset)
    let mut order = Vec::new();
    for a in need(&["axes"])?
        .as_array()
        .ok_or("the sidecar's axes is not a list")?
    {
        let an = a
            .get("name")
            .and_then(Value::as_str)
            .ok_or("an axis lacks its name")?;
        let mut o = Map::new();
        for k in ["size", "range", "convention"] {
            o.insert(
                k.into(),
                a.get(k)
                    .cloned()
                    .ok_or_else(|| format!("axis {an} lacks {k}"))?,
            );
        }
        if let Some(w) = a.get("warp") {
            o.insert(
                "warp".into(),
                w.get("name")
                    .cloned()
                    .ok_or_else(|| format!("axis {an}'s warp lacks its name"))?,
            );
        }
        if let Some(c) = a.get("clamp") {
            o.insert("clamp".into(), c.clone());
        }
        if let Some(q) = a.get("quantity").and_then(Value::as_str).and_then(|q| {
            q.strip_prefix("roughness:")
                .or_else(|| q.strip_prefix("fresnel:"))
        }) {
            o.insert("quantity".into(), json!(q));
        }
        axes.insert(an.into(), Value::Object(o));
        order.push(json!(an));
    }
    let mut t = Map::new();
    t.insert("name".into(), name);
    t.insert("kind".into(), kind.clone());
    t.insert("model".into(), Value::Object(model));
    t.insert("axes".into(), Value::Object(axes.clone()));
    if let Some(c) = get(&["ltc", "channels"]) {
        if kind == json!("ltc") {
            t.insert("ltc".into(), json!({ "channels": c }));
        }
    }
    if kind == json!("dfg") {
        if let Some(l) = get(&["model", "split_sum", "layout"]) {
            t.insert("layout".into(), l.clone());
        }
        if get(&["model", "cloth"]).is_some() {
            t.insert("cloth".into(), json!(true));
        }
        if let Some(a) = get(&["model", "cloth", "alpha_min"]) {
            t.insert("cloth_alpha_min".into(), a.clone());
        }
    }
    t.insert("storage".into(), need(&["storage", "texel_type"])?.clone());
    t.insert(
        "tolerance".into(),
        need(&["quadrature", "tolerance"])?.clone(),
    );
    if let Some(s) = get(&["storage", "scale"]) {
        t.insert("scale".into(), s.clone());
    }
    if let Some(a) = get(&["quadrature", "accept_error_estimate"]) {
        t.insert("accept_error_estimate".into(), a.clone());
    }
    if let Some(e) = get(&["engine", "name"]) {
        t.insert("engine".into(), e.clone());
    }
    if let Some(Value::Object(f)) = get(&["fit"]) {
        let mut f = f.clone();
        f.remove("sidecar");
        t.insert("fit".into(), Value::Object(f));
    }
    t.insert("axis_order".into(), Value::Array(order));
    // the preset's `channels`, which each stored channel states when it was set
    let stores: Vec<Value> = get(&["channels"])
        .and_then(Value::as_array)
        .map_or(&[][..], Vec::as_slice)
        .iter()
        .filter_map(|c| c.get("stores").cloned())
        .collect();
    if !stores.is_empty() {
        t.insert("channels".into(), Value::Array(stores));
    }
    if axes.len() == 3 {
        if let Some(l) = get(&["storage", "ktx2", "layout_3d"]) {
            t.insert("layout_3d".into(), l.clone());
        }
    }
    let preset = json!({"schema": crate::preset::SCHEMA, "tables": [Value::Object(t)]});
    let p = crate::preset::parse(&preset.to_string(), "sidecar", "sidecar")
        .map_err(|e| format!("the sidecar does not describe a valid table: {e}"))?;
    Ok(p.tables.into_iter().next().expect("one table"))
}

fn generic_axes(sizes: &[usize]) -> Vec<Axis> {
    sizes
        .iter()
        .zip(["x", "y", "z"])
        .map(|(&n, name)| Axis {
            name: name.into(),
            quantity: Quantity::Cosine,
            size: n,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        })
        .collect()
}

/// Parses our EXR `axisK` attribute: `name quantity convention [lo, hi] N texels`, then
/// `warp NAME` and `clamp [a, b]` where set.
fn parse_axis_attribute(s: &str) -> Option<Axis> {
    let w: Vec<&str> = s.split_whitespace().collect();
    if w.len() < 7 || w[6] != "texels" {
        return None;
    }
    let mut rest = &w[7..];
    let mut warp = crate::lut::Warp::Linear;
    if let ["warp", name, tail @ ..] = rest {
        warp = crate::lut::Warp::ALL
            .into_iter()
            .find(|x| x.name() == *name)?;
        rest = tail;
    }
    let mut clamp = None;
    if let ["clamp", a, b, tail @ ..] = rest {
        let a: f64 = a.strip_prefix('[')?.strip_suffix(',')?.parse().ok()?;
        let b: f64 = b.strip_suffix(']')?.parse().ok()?;
        clamp = Some([a, b]);
        rest = tail;
    }
    if !rest.is_empty() {
        return None;
    }
    let quantity = if w[1] == "cosine" {
        Quantity::Cosine
    } else if w[1] == "anisotropy" {
        Quantity::Anisotropy
    } else if w[1] == "form-factor" {
        Quantity::FormFactor
    } else if let Some(q) = w[1].strip_prefix("fresnel:") {
        Quantity::Fresnel(crate::model::FresnelQuantity::from_name(q)?)
    } else {
        let q = w[1].strip_prefix("roughness:")?;
        Quantity::Roughness(serde_json::from_value::<RoughnessQuantity>(json!(q)).ok()?)
    };
    let convention = serde_json::from_value::<Convention>(json!(w[2])).ok()?;
    let lo: f64 = w[3].strip_prefix('[')?.strip_suffix(',')?.parse().ok()?;
    let hi: f64 = w[4].strip_suffix(']')?.parse().ok()?;
    Some(Axis {
        name: w[0].into(),
        quantity,
        size: w[5].parse().ok()?,
        range: [lo, hi],
        convention,
        warp,
        clamp,
    })
}

fn mismatch(path: &Path, what: String) -> ReadError {
    ReadError::Input(format!(
        "{}: does not match its sidecar: {what}",
        path.display()
    ))
}

type Facts = Vec<(String, String)>;

fn read_exr(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Facts), ReadError> {
    let not_ours = |why: String| {
        ReadError::Input(format!(
            "{}: not an EXR file brdfbake wrote ({why})",
            path.display()
        ))
    };
    if !bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        return Err(not_ours("no OpenEXR magic number".into()));
    }
    let (w, h, channels, attrs) = decode_exr(bytes).map_err(not_ours)?;
    let facts: Facts = attrs
        .iter()
        .filter_map(|(k, v)| Some((k.strip_prefix(ATTRIBUTE_PREFIX)?.to_string(), v.clone())))
        .collect();
    if !facts
        .iter()
        .any(|(k, v)| k == "schema" && v == meta::SCHEMA)
    {
        return Err(not_ours(format!(
            "no {ATTRIBUTE_PREFIX}schema = {} header attribute",
            meta::SCHEMA
        )));
    }
    let (axes, chans) = match table {
        Some(t) => (t.stored_axes(), t.stored_channels()),
        None => {
            let mut axes = Vec::new();
            for k in 0..3 {
                if let Some((_, v)) = facts.iter().find(|(n, _)| *n == format!("axis{k}")) {
                    axes.push(parse_axis_attribute(v).ok_or_else(|| {
                        not_ours(format!(
                            "unreadable {ATTRIBUTE_PREFIX}axis{k} attribute {v:?}"
                        ))
                    })?);
                }
            }
            if axes.is_empty() {
                axes = generic_axes(&[w, h]);
            }
            let chans = channels
                .iter()
                .map(|(n, _)| Channel {
                    name: n.clone(),
                    meaning: String::new(),
                })
                .collect();
            (axes, chans)
        }
    };
    let nx = axes.first().map_or(1, |a| a.size);
    let rows: usize = axes.iter().skip(1).map(|a| a.size).product();
    if (w, h) != (nx, rows) {
        return Err(mismatch(
            path,
            format!("the image is {w}x{h}, the axes need {nx}x{rows}"),
        ));
    }
    let nc = chans.len();
    let mut data = vec![0f32; w * h * nc];
    for (c, ch) in chans.iter().enumerate() {
        let (_, values) = channels
            .iter()
            .find(|(n, _)| *n == ch.name)
            .ok_or_else(|| {
                mismatch(
                    path,
                    format!(
                        "no channel {:?} (the file has {})",
                        ch.name,
                        channels
                            .iter()
                            .map(|(n, _)| n.as_str())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?;
        if values.len() != w * h {
            return Err(mismatch(
                path,
                format!("channel {} has {} samples", ch.name, values.len()),
            ));
        }
        for (i, v) in values.iter().enumerate() {
            data[i * nc + c] = *v;
        }
    }
    if channels.len() != nc {
        return Err(mismatch(
            path,
            format!("{} channels, the sidecar lists {nc}", channels.len()),
        ));
    }
    Ok((
        Lut {
            axes,
            channels: chans,
            data,
            error_estimate: vec![f64::NAN; nc],
            evaluations: 0,
        },
        facts,
    ))
}

/// The KTX 2.0 file identifier (KTX 2.0 specification, section 3.1).
const KTX2_IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

/// Checks what `ktx2::Reader::new` (0.5) indexes without bounds checks, so that a hostile
/// file gets an error instead of a panic (both found by the `readback_ktx2` fuzz target,
/// docs/fuzzing.md): the data format descriptor (DFD; offset and length at bytes 48 and 52
/// of the header, KTX 2.0 §3.1) must lie within the file and hold at least its 4-byte total
/// size, and no basic DFD block may store a texel block dimension of 255 (stored as
/// dimension − 1, Khronos Data Format 1.3 §5.7; the reader adds 1 in a `u8`).
fn ktx2_precheck(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(&KTX2_IDENTIFIER) {
        return Err(if KTX2_IDENTIFIER.starts_with(bytes) {
            "the file is truncated: shorter than the KTX 2.0 identifier".into()
        } else {
            "no KTX 2.0 identifier".into()
        });
    }
    if bytes.len() < 80 {
        return Err("the file is truncated: shorter than the 80-byte KTX2 header".into());
    }
    let u32_at = |b: &[u8], o: usize| u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
    let (off, len) = (u32_at(bytes, 48) as u64, u32_at(bytes, 52) as u64);
    if len < 4 || off + len > bytes.len() as u64 {
        return Err(format!(
            "the file is truncated or corrupt: its data format descriptor (bytes {off}..{}) does not lie within its {} bytes",
            off + len,
            bytes.len()
        ));
    }
    let mut dfd = &bytes[off as usize + 4..(off + len) as usize];
    while dfd.len() >= 16 {
        let word = u32_at(dfd, 0);
        let size = u16::from_le_bytes([dfd[6], dfd[7]]) as usize;
        // vendor id (17 bits) 0 and descriptor type (15 bits) 0: the basic block
        if word == 0 && dfd[12..16].contains(&255) {
            return Err("corrupt data format descriptor: a texel block dimension of 256".into());
        }
        if size < 8 || size > dfd.len() {
            break; // the reader reports a malformed block size itself
        }
        dfd = &dfd[size..];
    }
    Ok(())
}

fn read_ktx2(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Facts), ReadError> {
    let not_ours = |why: String| {
        ReadError::Input(format!(
            "{}: not a KTX2 file brdfbake wrote ({why})",
            path.display()
        ))
    };
    ktx2_precheck(bytes).map_err(not_ours)?;
    // ktx2_precheck covers the panics known in ktx2 0.5; a panic still left in the parser
    // becomes an error here rather than a crash
    let parsed = std::panic::catch_unwind(|| ::ktx2::Reader::new(bytes))
        .map_err(|_| not_ours("malformed KTX2: the KTX2 parser failed on it".into()))?;
    let r = parsed.map_err(|e| {
        not_ours(match e {
            ::ktx2::ParseError::UnexpectedEnd => {
                "the file is truncated: its header or index points past its end".into()
            }
            ::ktx2::ParseError::BadMagic => "no KTX 2.0 identifier".into(),
            e => format!("invalid KTX2: {e}"),
        })
    })?;
    let writer = r.writer().unwrap_or("").trim_end_matches('\0').to_string();
    if !writer.starts_with("brdfbake ") {
        let shown: String = writer.chars().take(80).collect();
        return Err(not_ours(if writer.is_empty() {
            "it has no KTXwriter".to_string()
        } else {
            format!("its KTXwriter is \"{}\"", shown.escape_default())
        }));
    }
    let hd = r.header();
    let (storage, components) = match hd.format.map(|f| (f, crate::encode::ktx2::storage_of(f))) {
        Some((_, Some(held))) => held,
        Some((f, None)) => {
            return Err(not_ours(format!(
                "its vkFormat is {f:?}; brdfbake writes R, RG or RGBA in 16- or 32-bit float or 8- or 16-bit UNORM"
            )))
        }
        None => {
            return Err(not_ours(
                "its vkFormat is undefined (0: a Basis Universal or other supercompressed file?); \
                 brdfbake writes R, RG or RGBA in 16- or 32-bit float or 8- or 16-bit UNORM"
                    .into(),
            ))
        }
    };
    let comp_bytes = storage.bytes();
    if let Some(t) = table {
        if t.spec.storage != storage {
            return Err(mismatch(
                path,
                format!(
                    "its vkFormat {:?} stores {}, the sidecar says \"storage\": {:?}",
                    hd.format.expect("known"),
                    storage.name(),
                    t.spec.storage.name()
                ),
            ));
        }
    }
    if hd.level_count != 1 {
        return Err(not_ours(format!(
            "levelCount {}: brdfbake writes one level",
            hd.level_count
        )));
    }
    match hd.supercompression_scheme {
        None | Some(::ktx2::SupercompressionScheme::Zstandard) => {}
        Some(s) => {
            return Err(not_ours(format!(
                "supercompressionScheme {s:?}: brdfbake writes none or Zstandard"
            )))
        }
    }
    let (w, h) = (hd.pixel_width as usize, hd.pixel_height.max(1) as usize);
    // u64: depth × layers of a hostile header overflows u32 (found by the readback_ktx2
    // fuzz target); the product of all sizes is checked against the level's bytes below
    let d = (hd.pixel_depth.max(1) as u64 * hd.layer_count.max(1) as u64) as usize;
    let mut facts: Facts = vec![
        ("writer".into(), writer),
        (
            "vk_format".into(),
            format!("{:?}", hd.format.expect("checked")),
        ),
        (
            "size".into(),
            format!(
                "{w}x{h}, depth {}, layers {}",
                hd.pixel_depth, hd.layer_count
            ),
        ),
    ];
    for (k, v) in r.key_value_data() {
        if k == "KTXorientation" {
            facts.push((
                "orientation".into(),
                String::from_utf8_lossy(v)
                    .trim_end_matches('\0')
                    .to_string(),
            ));
        }
    }
    let level = r
        .levels()
        .next()
        .ok_or_else(|| not_ours("no level".into()))?;
    // checked: 2^32 × 2^32 × 2^64 × 16 overflows even u128 (fuzz crash 4)
    let need = [h, d, components, comp_bytes]
        .iter()
        .try_fold(w as u128, |n, &k| n.checked_mul(k as u128));
    // (a supercompressed level states its inflated size, which must be the texels')
    let stored = match hd.supercompression_scheme {
        None => level.data.len() as u128,
        Some(_) => level.uncompressed_byte_length as u128,
    };
    if need != Some(stored) {
        let need = need.map_or("more than 2^128".to_string(), |n| n.to_string());
        return Err(not_ours(format!(
            "level size does not match its header ({} bytes, the header's {w} x {h} x {d} texels need {need})",
            level.data.len()
        )));
    }
    if hd.supercompression_scheme.is_some() {
        facts.push((
            "supercompression".into(),
            format!(
                "zstd ({} bytes, {} inflated)",
                level.data.len(),
                level.uncompressed_byte_length
            ),
        ));
    }
    let level_data: std::borrow::Cow<[u8]> = match hd.supercompression_scheme {
        None => level.data.into(),
        Some(_) if level.uncompressed_byte_length > MAX_KTX2_INFLATED_BYTES => {
            return Err(not_ours(format!(
                "its level states {} inflated bytes, more than the largest table brdfbake writes ({MAX_KTX2_INFLATED_BYTES})",
                level.uncompressed_byte_length
            )))
        }
        Some(_) => crate::encode::zstd::decompress(level.data, level.uncompressed_byte_length as usize)
            .map_err(|e| not_ours(format!("its level: {e}")))?
            .into(),
    };
    texture_lut(
        path,
        &level_data,
        [w, h, d],
        storage,
        components,
        table,
        facts,
    )
}

fn read_dds(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Facts), ReadError> {
    let im = crate::encode::dds::read(bytes).map_err(|why| {
        ReadError::Input(format!(
            "{}: not a DDS file brdfbake wrote ({why})",
            path.display()
        ))
    })?;
    let (components, storage) = (im.components, im.storage);
    let format_name = crate::encode::dds::dxgi_format(components, storage).1;
    if let Some(t) = table {
        if t.spec.storage != storage {
            return Err(mismatch(
                path,
                format!(
                    "its dxgiFormat {format_name} stores {}, the sidecar says \"storage\": {:?}",
                    storage.name(),
                    t.spec.storage.name()
                ),
            ));
        }
        let volume = t.stored_axes().len() == 3 && t.layout_3d == crate::preset::Layout3d::Volume;
        if volume != im.volume {
            return Err(mismatch(
                path,
                format!(
                    "it is a {}, the sidecar's table a {}",
                    if im.volume {
                        "volume texture"
                    } else {
                        "2D (array) texture"
                    },
                    if volume {
                        "volume"
                    } else {
                        "2D texture or array"
                    }
                ),
            ));
        }
    }
    let facts: Facts = vec![
        (
            "dxgi_format".into(),
            format!("DXGI_FORMAT_{format_name} ({})", im.dxgi_format),
        ),
        (
            "size".into(),
            format!(
                "{}x{}, depth {}, array size {}",
                im.width, im.height, im.depth, im.array_size
            ),
        ),
    ];
    let d = im.depth.max(im.array_size) as usize;
    texture_lut(
        path,
        &bytes[im.data_offset..],
        [im.width as usize, im.height as usize, d],
        storage,
        components,
        table,
        facts,
    )
}

/// The table held by a texture container's texel bytes (`data`: `size[0]` × `size[1]` ×
/// `size[2]` texels of `components` components in `storage`, interleaved, x fastest), with
/// the sidecar's axes and channels when there is one.
fn texture_lut(
    path: &Path,
    data: &[u8],
    [w, h, d]: [usize; 3],
    storage: crate::table::Storage,
    components: usize,
    table: Option<&PresetTable>,
    facts: Facts,
) -> Result<(Lut, Facts), ReadError> {
    use crate::table::Storage;
    let comp_bytes = storage.bytes();
    let texels = w * h * d; // ≤ the level's byte count: cannot overflow
    let raw: Vec<f32> = data
        .chunks_exact(comp_bytes)
        .map(|b| match storage {
            Storage::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            Storage::F16 => half::f16::from_le_bytes([b[0], b[1]]).to_f32(),
            Storage::Unorm8 => crate::encode::unorm::value(b[0] as u16, 255) as f32,
            Storage::Unorm16 => {
                crate::encode::unorm::value(u16::from_le_bytes([b[0], b[1]]), 65535) as f32
            }
        })
        .collect();
    let (axes, chans) = match table {
        Some(t) => (t.stored_axes(), t.stored_channels()),
        None => {
            let sizes: Vec<usize> = if d > 1 {
                vec![w, h, d]
            } else if h > 1 {
                vec![w, h]
            } else {
                vec![w]
            };
            let chans = ["R", "G", "B", "A"][..components]
                .iter()
                .map(|n| Channel {
                    name: n.to_string(),
                    meaning: String::new(),
                })
                .collect();
            (generic_axes(&sizes), chans)
        }
    };
    let n: usize = axes.iter().map(|a| a.size).product();
    let nc = chans.len();
    let expected = if nc == 3 { 4 } else { nc };
    if n != texels || expected != components {
        return Err(mismatch(
            path,
            format!(
                "{texels} texels of {components} components, the sidecar describes {n} texels of {nc} channels"
            ),
        ));
    }
    let data: Vec<f32> = raw
        .chunks_exact(components)
        .flat_map(|t| t[..nc].to_vec())
        .collect();
    Ok((
        Lut {
            axes,
            channels: chans,
            data,
            error_estimate: vec![f64::NAN; nc],
            evaluations: 0,
        },
        facts,
    ))
}

/// The largest supercompressed KTX2 level inflated: the largest table
/// ([`crate::table::spec::MAX_TEXELS`]) of 4 channels of 32 bits.
pub const MAX_KTX2_INFLATED_BYTES: u64 = crate::table::spec::MAX_TEXELS as u64 * 16;

/// The largest png-data image read back: the largest table (2^24 texels) of 4 channels of
/// 16 bits, plus room for the text chunks.
pub const MAX_PNG_DECODED_BYTES: usize = (1 << 24) * 8 + (1 << 20);

fn read_png_data(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Facts), ReadError> {
    use crate::table::Storage;
    let not_ours = |why: String| {
        ReadError::Input(format!(
            "{}: not a png-data file brdfbake wrote ({why}); a .png is read back only as png-data \
             (the texels of a unorm table), never a preview (*.preview-*.png, for people)",
            path.display()
        ))
    };
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Err(not_ours("no PNG signature".into()));
    }
    let mut decoder = ::png::Decoder::new_with_limits(
        std::io::Cursor::new(bytes),
        ::png::Limits {
            bytes: MAX_PNG_DECODED_BYTES,
        },
    );
    // the samples as stored: no expansion, no 16-to-8 stripping, no gamma
    decoder.set_transformations(::png::Transformations::IDENTITY);
    let mut reader = decoder
        .read_info()
        .map_err(|e| not_ours(format!("invalid PNG: {e}")))?;
    let info = reader.info();
    let text: Vec<(String, String)> = info
        .uncompressed_latin1_text
        .iter()
        .map(|t| (t.keyword.clone(), t.text.clone()))
        .chain(
            info.utf8_text
                .iter()
                .filter_map(|t| Some((t.keyword.clone(), t.get_text().ok()?))),
        )
        .collect();
    let (w, h) = (info.width as usize, info.height as usize);
    let (color, depth) = (info.color_type, info.bit_depth);
    // (before any allocation: a hostile header may claim 2^31 x 2^31 pixels)
    let decoded = (w as u128) * (h as u128) * 8;
    if decoded > MAX_PNG_DECODED_BYTES as u128 {
        return Err(not_ours(format!(
            "its header claims {w} x {h} pixels, more than a table brdfbake writes (at most 2^24 texels)"
        )));
    }
    let facts: Facts = text
        .iter()
        .filter_map(|(k, v)| Some((k.strip_prefix(ATTRIBUTE_PREFIX)?.to_string(), v.clone())))
        .collect();
    let fact = |k: &str| facts.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    if fact("schema") != Some(meta::SCHEMA) {
        return Err(not_ours(format!(
            "no {ATTRIBUTE_PREFIX}schema = {} text chunk",
            meta::SCHEMA
        )));
    }
    if fact("note") == Some(crate::encode::png::NOTE) {
        return Err(ReadError::Input(format!(
            "{}: a preview for people (its values are mapped to [min, max] of each channel), not the \
             table's texels: read the table's .exr, .ktx2 or png-data .png",
            path.display()
        )));
    }
    if fact("note") == Some(crate::encode::rgbd::NOTE) {
        return Err(ReadError::Input(format!(
            "{}: a png-rgbd image (Babylon.js' RGBD encoding: 8-bit codes with a shared divisor, \
             its rounding in the sidecar's storage.rgbd), not texels this command reads: read the \
             table's .exr, .ktx2 or .npy (bake it with --format exr,png-rgbd)",
            path.display()
        )));
    }
    if fact("note") != Some(crate::encode::png_data::NOTE) {
        return Err(not_ours(format!(
            "no {ATTRIBUTE_PREFIX}note = {:?} text chunk",
            crate::encode::png_data::NOTE
        )));
    }
    let storage = match depth {
        ::png::BitDepth::Eight => Storage::Unorm8,
        ::png::BitDepth::Sixteen => Storage::Unorm16,
        d => {
            return Err(not_ours(format!(
                "bit depth {d:?}; png-data is 8- or 16-bit"
            )))
        }
    };
    let components = match color {
        ::png::ColorType::Grayscale => 1,
        ::png::ColorType::Rgb => 3,
        ::png::ColorType::Rgba => 4,
        c => {
            return Err(not_ours(format!(
                "colour type {c:?}; png-data is greyscale, RGB or RGBA"
            )))
        }
    };
    let (axes, chans) = match table {
        Some(t) => {
            if t.spec.storage != storage {
                return Err(mismatch(
                    path,
                    format!(
                        "its {}-bit samples store {}, the sidecar says \"storage\": {:?}",
                        storage.bytes() * 8,
                        storage.name(),
                        t.spec.storage.name()
                    ),
                ));
            }
            (t.stored_axes(), t.stored_channels())
        }
        None => {
            let mut axes = Vec::new();
            for k in 0..3 {
                if let Some(v) = fact(&format!("axis{k}")) {
                    axes.push(parse_axis_attribute(v).ok_or_else(|| {
                        not_ours(format!("unreadable {ATTRIBUTE_PREFIX}axis{k} text {v:?}"))
                    })?);
                }
            }
            if axes.is_empty() {
                axes = generic_axes(&[w, h]);
            }
            let names: &[&str] = match components {
                1 => &["grey"],
                3 => &["R", "G", "B"],
                _ => &["R", "G", "B", "A"],
            };
            let chans = names
                .iter()
                .map(|n| Channel {
                    name: n.to_string(),
                    meaning: String::new(),
                })
                .collect();
            (axes, chans)
        }
    };
    let nc = chans.len();
    let expected = match nc {
        1 => 1,
        2 | 3 => 3,
        _ => 4,
    };
    let nx = axes.first().map_or(1, |a| a.size);
    let rows: usize = axes.iter().skip(1).map(|a| a.size).product();
    if (w, h) != (nx, rows) || expected != components {
        return Err(mismatch(
            path,
            format!(
                "the image is {w}x{h} with {components} component(s), the sidecar describes {nx}x{rows} texels of {nc} channel(s)"
            ),
        ));
    }
    let mut buf = vec![
        0u8;
        reader
            .output_buffer_size()
            .ok_or_else(|| not_ours("the image is too large".into()))?
    ];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| not_ours(format!("invalid PNG data: {e}")))?;
    let buf = &buf[..frame.buffer_size()];
    let max = storage.unorm_max().expect("unorm");
    let samples: Vec<u16> = match storage {
        Storage::Unorm8 => buf.iter().map(|&b| b as u16).collect(),
        _ => buf
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect(),
    };
    if samples.len() != w * h * components {
        return Err(not_ours(format!(
            "{} samples, the header's {w} x {h} x {components} need {}",
            samples.len(),
            w * h * components
        )));
    }
    let mut data = Vec::with_capacity(w * h * nc);
    for texel in samples.chunks_exact(components) {
        // (a 2-channel table's B is padding: 0)
        if nc == 2 && texel[2] != 0 {
            return Err(mismatch(
                path,
                "a two-channel table's B samples are 0 in png-data, this file's are not".into(),
            ));
        }
        data.extend(
            texel[..nc]
                .iter()
                .map(|&c| crate::encode::unorm::value(c, max) as f32),
        );
    }
    Ok((
        Lut {
            axes,
            channels: chans,
            data,
            error_estimate: vec![f64::NAN; nc],
            evaluations: 0,
        },
        facts,
    ))
}

/// Decodes the bytes of a png-data file as `read` does for `path` (no disk access), checked
/// against `table` when given.
pub fn read_png_data_bytes(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Vec<(String, String)>), ReadError> {
    read_png_data(path, bytes, table)
}

/// Per-channel statistics of stored texels.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ChannelStats {
    pub name: String,
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    pub nan: usize,
    pub inf: usize,
}

/// min/max/mean over finite texels, and the NaN and Inf counts, per channel.
pub fn stats(lut: &Lut) -> Vec<ChannelStats> {
    let nc = lut.channels.len();
    lut.channels
        .iter()
        .enumerate()
        .map(|(c, ch)| {
            let (mut min, mut max, mut sum, mut n, mut nan, mut inf) =
                (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0usize, 0, 0);
            for v in lut.data.iter().skip(c).step_by(nc.max(1)) {
                let v = *v as f64;
                if v.is_nan() {
                    nan += 1;
                } else if v.is_infinite() {
                    inf += 1;
                } else {
                    min = min.min(v);
                    max = max.max(v);
                    sum += v;
                    n += 1;
                }
            }
            ChannelStats {
                name: ch.name.clone(),
                min,
                max,
                mean: if n > 0 { sum / n as f64 } else { f64::NAN },
                nan,
                inf,
            }
        })
        .collect()
}

/// The exact value of every channel of `table` at the coordinates `x` (one per axis, in the
/// axes' own quantities), computed by the table module at tolerance `tol` (a one-texel table
/// at exactly those coordinates). Returns the values and their error estimates.
pub fn exact_at(
    table: &crate::table::TableSpec,
    x: &[f64],
    tol: f64,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    if table.kind.is_ltc() {
        return crate::table::ltc::exact_at(table, x, tol);
    }
    let mut spec = table.clone();
    spec.tolerance = tol;
    for (a, &v) in spec.axes.iter_mut().zip(x) {
        // the table holds f(clamp(x)) (lut::Axis): the exact value is there
        let v = a.clamped(v);
        a.size = 1;
        a.range = [v, v];
        a.convention = Convention::Centers;
        a.warp = crate::lut::Warp::Linear;
        a.clamp = None;
    }
    // the spec's messages speak of texels and conventions; here there is one point
    spec.validate().map_err(|e| {
        let e = e
            .split("; use the centers")
            .next()
            .unwrap_or("")
            .split(" (use the centers")
            .next()
            .unwrap_or("")
            .replace(": texel 0 is at", ": the point is at")
            .replace(": a texel is at", ": the point is at")
            .replace("every texel needs", "the model needs")
            .replace("a texel at cosine 0", "cosine 0")
            .replace("start the range at", "give a cosine of");
        format!("no exact value there: {e}")
    })?;
    use crate::table::{albedo, dfg, local, TableKind};
    if let Some(v) = crate::table::smooth_limit_at(&spec, [0, 0, 0]) {
        return Ok(v);
    }
    let f = match spec.kind {
        TableKind::Ndf | TableKind::G1 | TableKind::G2 | TableKind::Vgroove => {
            local::texel_fn(&spec)
        }
        TableKind::Albedo | TableKind::AlbedoAvg => albedo::texel_fn(&spec),
        TableKind::Dfg => dfg::texel_fn(&spec),
        TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
            crate::table::energy::texel_fn(&spec)
        }
        TableKind::DielectricAlbedo => crate::table::dielectric::texel_fn(&spec),
        TableKind::DielectricSchlick => crate::table::dielectric_schlick::texel_fn(&spec),
        TableKind::DielectricAlbedoAvg => crate::table::dielectric_average::texel_fn(&spec),
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => {
            crate::table::schlick_weight::texel_fn(&spec)
        }
        TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
            crate::table::classic::texel_fn(&spec)
        }
        TableKind::Ltc | TableKind::LtcSphere => unreachable!("handled above"),
    };
    let r = crate::quadrature::budget::with_budget(
        crate::quadrature::budget::INTEGRAL_EVAL_BUDGET,
        || f([0, 0, 0]),
    );
    Ok((r.value, r.error))
}

/// Decodes the bytes of an EXR file as `read` does for `path` (no disk access), checked
/// against `table` when given. The entry point of the `readback_exr` fuzz target.
pub fn read_exr_bytes(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Vec<(String, String)>), ReadError> {
    read_exr(path, bytes, table)
}

/// Decodes the bytes of a KTX2 file as `read` does for `path` (no disk access), checked
/// against `table` when given. The entry point of the `readback_ktx2` fuzz target.
pub fn read_ktx2_bytes(
    path: &Path,
    bytes: &[u8],
    table: Option<&PresetTable>,
) -> Result<(Lut, Vec<(String, String)>), ReadError> {
    read_ktx2(path, bytes, table)
}
