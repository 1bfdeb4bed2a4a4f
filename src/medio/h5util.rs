//! Thin HDF5 helpers shaped by what MED needs, each turning HDF5 failures
//! into a [`MedError`] that says which object of which file was involved.
//!
//! MED stores its strings as fixed-length ASCII attributes of exactly
//! `len + 1` bytes (libmed's habit; readers iterate steps in a wrong order
//! with other sizes), integers as 32- or 64-bit attributes, and names of
//! groups as arrays of 80 `int8`. These helpers hide those details.

use std::io::Read;
use std::path::Path;

use hdf5::plist::group_create::LinkCreationOrder;
use hdf5::types::{FixedAscii, TypeDescriptor, VarLenAscii, VarLenUnicode};
use hdf5::{Dataset, Datatype, File, Group, Location};

use super::{MedError, MedErrorKind};

/// Length of a MED group name (`GRO/NOM` entries), blank padded.
pub(crate) const LNAME: usize = 80;

/// Builds error values for one file.
#[derive(Clone, Copy)]
pub(crate) struct Ctx<'a> {
    pub path: &'a Path,
}

impl<'a> Ctx<'a> {
    pub fn err(&self, kind: MedErrorKind) -> MedError {
        MedError::new(self.path, kind)
    }
    pub fn inconsistent(&self, msg: impl Into<String>) -> MedError {
        self.err(MedErrorKind::Inconsistent(msg.into()))
    }
    pub fn h5(&self, what: &str, e: hdf5::Error) -> MedError {
        self.err(MedErrorKind::Hdf5(format!("{what}: {e}")))
    }
}

/// The HDF5 format signature, searched at offsets 0, 512, 1024, 2048...
/// (a user block may precede the superblock).
const SIGNATURE: [u8; 8] = [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'];

/// Opens a MED file read-only after checking it is HDF5 at all, so that a
/// random or text file gets "not an HDF5 file" instead of an HDF5 stack.
pub(crate) fn open_read(path: &Path) -> Result<File, MedError> {
    let ctx = Ctx { path };
    let mut f = std::fs::File::open(path)
        .map_err(|e| ctx.err(MedErrorKind::Io(format!("cannot open: {e}"))))?;
    let len = f
        .metadata()
        .map_err(|e| ctx.err(MedErrorKind::Io(format!("cannot stat: {e}"))))?
        .len();
    // A user block is at most a few MB; reading up to 8 MB covers it.
    let head_len = len.min(8 << 20) as usize;
    let mut head = vec![0u8; head_len];
    f.read_exact(&mut head)
        .map_err(|e| ctx.err(MedErrorKind::Io(format!("cannot read: {e}"))))?;
    let mut off = 0usize;
    let mut found = false;
    while off + SIGNATURE.len() <= head.len() {
        if head[off..off + SIGNATURE.len()] == SIGNATURE {
            found = true;
            break;
        }
        off = if off == 0 { 512 } else { off * 2 };
    }
    if !found {
        return Err(ctx.err(MedErrorKind::NotHdf5));
    }
    File::open(path).map_err(|e| {
        let msg = e.to_string();
        if msg.to_lowercase().contains("truncated") {
            ctx.err(MedErrorKind::Truncated(format!(
                "file size {len} bytes; {msg}"
            )))
        } else {
            ctx.err(MedErrorKind::Hdf5(format!("cannot open as HDF5: {msg}")))
        }
    })
}

/// Child group names of `g` that are groups (datasets are skipped), in
/// HDF5 name order.
pub(crate) fn child_groups(ctx: Ctx, g: &Group, what: &str) -> Result<Vec<String>, MedError> {
    let names = g.member_names().map_err(|e| ctx.h5(what, e))?;
    Ok(names.into_iter().filter(|n| g.group(n).is_ok()).collect())
}

pub(crate) fn has_attr(loc: &Location, name: &str) -> bool {
    loc.attr_names()
        .map(|v| v.iter().any(|n| n == name))
        .unwrap_or(false)
}

/// Integer attribute, whatever its stored width (libmed builds differ).
pub(crate) fn int_attr(ctx: Ctx, loc: &Location, name: &str, what: &str) -> Result<i64, MedError> {
    let a = loc
        .attr(name)
        .map_err(|_| ctx.inconsistent(format!("{what}: attribute @{name} is missing")))?;
    a.read_scalar::<i64>()
        .map_err(|e| ctx.inconsistent(format!("{what}: attribute @{name} is not an integer: {e}")))
}

pub(crate) fn opt_int_attr(
    ctx: Ctx,
    loc: &Location,
    name: &str,
    what: &str,
) -> Result<Option<i64>, MedError> {
    if has_attr(loc, name) {
        int_attr(ctx, loc, name, what).map(Some)
    } else {
        Ok(None)
    }
}

pub(crate) fn f64_attr(ctx: Ctx, loc: &Location, name: &str, what: &str) -> Result<f64, MedError> {
    let a = loc
        .attr(name)
        .map_err(|_| ctx.inconsistent(format!("{what}: attribute @{name} is missing")))?;
    a.read_scalar::<f64>()
        .map_err(|e| ctx.inconsistent(format!("{what}: attribute @{name} is not a number: {e}")))
}

/// String attribute (fixed or variable length), trailing NULs removed,
/// trailing blanks kept: MED pads names inside longer strings with blanks
/// and the caller knows the field width.
pub(crate) fn str_attr(
    ctx: Ctx,
    loc: &Location,
    name: &str,
    what: &str,
) -> Result<String, MedError> {
    let a = loc
        .attr(name)
        .map_err(|_| ctx.inconsistent(format!("{what}: attribute @{name} is missing")))?;
    let bad = |e: hdf5::Error| {
        ctx.inconsistent(format!("{what}: attribute @{name} is not a string: {e}"))
    };
    let dt = a.dtype().map_err(bad)?;
    let desc = dt.to_descriptor().map_err(bad)?;
    let bytes: Vec<u8> = match desc {
        TypeDescriptor::FixedAscii(n) | TypeDescriptor::FixedUnicode(n) => {
            if n > 65536 {
                return Err(ctx.inconsistent(format!(
                    "{what}: attribute @{name} is an implausibly long string ({n} bytes)"
                )));
            }
            if n <= 256 {
                a.read_scalar::<FixedAscii<256>>()
                    .map_err(bad)?
                    .as_bytes()
                    .to_vec()
            } else {
                a.read_scalar::<FixedAscii<65536>>()
                    .map_err(bad)?
                    .as_bytes()
                    .to_vec()
            }
        }
        TypeDescriptor::VarLenAscii => a
            .read_scalar::<VarLenAscii>()
            .map_err(bad)?
            .as_bytes()
            .to_vec(),
        TypeDescriptor::VarLenUnicode => a
            .read_scalar::<VarLenUnicode>()
            .map_err(bad)?
            .as_bytes()
            .to_vec(),
        other => {
            return Err(ctx.inconsistent(format!(
                "{what}: attribute @{name} should be a string, found {other:?}"
            )))
        }
    };
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    Ok(String::from_utf8_lossy(&bytes[..end]).into_owned())
}

/// Reads a dataset of integers of any width into i64.
pub(crate) fn read_ints(ctx: Ctx, ds: &Dataset, what: &str) -> Result<Vec<i64>, MedError> {
    ds.read_raw::<i64>()
        .map_err(|e| ctx.inconsistent(format!("{what}: cannot read as integers: {e}")))
}

pub(crate) fn read_f64s(ctx: Ctx, ds: &Dataset, what: &str) -> Result<Vec<f64>, MedError> {
    ds.read_raw::<f64>().map_err(|e| {
        ctx.inconsistent(format!(
            "{what}: cannot read as floating-point numbers: {e}"
        ))
    })
}

/// Reads a MED name table of `count` names of `LNAME` characters: either
/// `count` elements of `H5T_ARRAY{[80] int8}` (MED 3/4), a flat int8 dataset
/// of `80*count` characters, or fixed strings of 80. Blanks and NULs are
/// trimmed from each name.
pub(crate) fn read_names80(ctx: Ctx, ds: &Dataset, what: &str) -> Result<Vec<String>, MedError> {
    let bad = |e: hdf5::Error| ctx.inconsistent(format!("{what}: cannot read names: {e}"));
    let desc = ds.dtype().and_then(|d| d.to_descriptor()).map_err(bad)?;
    let raw: Vec<u8> = match desc {
        TypeDescriptor::FixedArray(ref inner, LNAME)
            if matches!(
                **inner,
                TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_)
            ) =>
        {
            ds.read_raw::<[i8; LNAME]>()
                .map_err(bad)?
                .iter()
                .flat_map(|a| a.iter().map(|&c| c as u8))
                .collect()
        }
        TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => ds
            .read_raw::<i8>()
            .map_err(bad)?
            .iter()
            .map(|&c| c as u8)
            .collect(),
        TypeDescriptor::FixedAscii(LNAME) | TypeDescriptor::FixedUnicode(LNAME) => {
            let v = ds.read_raw::<FixedAscii<LNAME>>().map_err(bad)?;
            let mut out = Vec::with_capacity(v.len() * LNAME);
            for s in v {
                let mut b = s.as_bytes().to_vec();
                b.resize(LNAME, b' ');
                out.extend(b);
            }
            out
        }
        other => {
            return Err(ctx.inconsistent(format!(
                "{what}: names should be arrays of {LNAME} characters, found {other:?}"
            )))
        }
    };
    if !raw.len().is_multiple_of(LNAME) {
        return Err(ctx.inconsistent(format!(
            "{what}: {} characters is not a whole number of {LNAME}-character names",
            raw.len()
        )));
    }
    Ok(raw
        .chunks(LNAME)
        .map(|c| {
            let end = c.iter().position(|&b| b == 0).unwrap_or(c.len());
            String::from_utf8_lossy(&c[..end]).trim_end().to_string()
        })
        .collect())
}

// ---------------------------------------------------------------- writing

/// Creates a group whose links are tracked and indexed by creation order:
/// libmed iterates families and field steps that way and fails without it.
pub(crate) fn ordered_group(ctx: Ctx, parent: &Group, name: &str) -> Result<Group, MedError> {
    parent
        .create_group_builder()
        .with_gcpl(|p| p.link_creation_order(LinkCreationOrder::Indexed))
        .create(name)
        .map_err(|e| ctx.h5(&format!("creating group {name}"), e))
}

pub(crate) fn group(ctx: Ctx, parent: &Group, name: &str) -> Result<Group, MedError> {
    parent
        .create_group(name)
        .map_err(|e| ctx.h5(&format!("creating group {name}"), e))
}

pub(crate) fn put_int(ctx: Ctx, loc: &Location, name: &str, v: i64) -> Result<(), MedError> {
    loc.new_attr::<i64>()
        .create(name)
        .and_then(|a| a.write_scalar(&v))
        .map_err(|e| ctx.h5(&format!("writing attribute @{name}"), e))
}

pub(crate) fn put_f64(ctx: Ctx, loc: &Location, name: &str, v: f64) -> Result<(), MedError> {
    loc.new_attr::<f64>()
        .create(name)
        .and_then(|a| a.write_scalar(&v))
        .map_err(|e| ctx.h5(&format!("writing attribute @{name}"), e))
}

/// Fixed-length ASCII string attribute of exactly `text.len() + 1` bytes,
/// NUL padded, as libmed writes it. The value goes through a wider memory
/// string type that HDF5 converts to the stored size.
pub(crate) fn put_str(ctx: Ctx, loc: &Location, name: &str, text: &str) -> Result<(), MedError> {
    let fail = |e: hdf5::Error| ctx.h5(&format!("writing attribute @{name}"), e);
    if !text.is_ascii() {
        return Err(ctx.err(MedErrorKind::InvalidInput(format!(
            "attribute @{name}: '{text}' is not ASCII"
        ))));
    }
    let dt =
        Datatype::from_descriptor(&TypeDescriptor::FixedAscii(text.len() + 1)).map_err(fail)?;
    let attr = loc
        .new_attr_builder()
        .empty_as(&dt)
        .create(name)
        .map_err(fail)?;
    let too_long = || {
        ctx.err(MedErrorKind::InvalidInput(format!(
            "attribute @{name}: string of {} characters is too long",
            text.len()
        )))
    };
    if text.len() < 256 {
        let v = FixedAscii::<256>::from_ascii(text).map_err(|_| too_long())?;
        attr.write_scalar(&v).map_err(fail)
    } else {
        let v = FixedAscii::<65536>::from_ascii(text).map_err(|_| too_long())?;
        attr.write_scalar(&v).map_err(fail)
    }
}

pub(crate) fn put_i64s(ctx: Ctx, g: &Group, name: &str, data: &[i64]) -> Result<Dataset, MedError> {
    g.new_dataset_builder()
        .with_data(data)
        .create(name)
        .map_err(|e| ctx.h5(&format!("writing dataset {name}"), e))
}

pub(crate) fn put_f64s(ctx: Ctx, g: &Group, name: &str, data: &[f64]) -> Result<Dataset, MedError> {
    g.new_dataset_builder()
        .with_data(data)
        .create(name)
        .map_err(|e| ctx.h5(&format!("writing dataset {name}"), e))
}

/// Name table as `H5T_ARRAY{[80] int8}`, blank padded, one element per name.
pub(crate) fn put_names80(
    ctx: Ctx,
    g: &Group,
    name: &str,
    names: &[&str],
) -> Result<Dataset, MedError> {
    let rows: Vec<[i8; LNAME]> = names
        .iter()
        .map(|n| {
            let mut row = [b' ' as i8; LNAME];
            for (k, b) in n.bytes().take(LNAME).enumerate() {
                row[k] = b as i8;
            }
            row
        })
        .collect();
    g.new_dataset_builder()
        .with_data(&rows)
        .create(name)
        .map_err(|e| ctx.h5(&format!("writing dataset {name}"), e))
}

/// Pads (or cuts) `s` to `n` characters with blanks: MED's layout of
/// component and axis names, 16 characters each.
pub(crate) fn pad(s: &str, n: usize) -> String {
    let mut out: String = s.chars().take(n).collect();
    while out.len() < n {
        out.push(' ');
    }
    out
}

/// Splits a concatenation of `n`-character names (component names, axis
/// names) into trimmed names.
pub(crate) fn split_fixed(s: &str, n: usize) -> Vec<String> {
    let b = s.as_bytes();
    b.chunks(n)
        .map(|c| String::from_utf8_lossy(c).trim().to_string())
        .collect()
}
