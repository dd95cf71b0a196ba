//! DirectDraw Surface (DDS) files of two-channel float textures, the container engines load
//! lookup tables from: writing (the `dfg` program) and reading back (its tests).
//!
//! Layout, all fields little-endian `u32` (Microsoft, "Programming Guide for DDS", the
//! `DDS_HEADER`, `DDS_PIXELFORMAT` and `DDS_HEADER_DXT10` structures):
//!
//! | offset | field | value |
//! |---:|---|---|
//! | 0 | magic | `"DDS "` (`0x20534444`) |
//! | 4 | `dwSize` | 124 |
//! | 8 | `dwFlags` | `CAPS \| HEIGHT \| WIDTH \| PITCH \| PIXELFORMAT` = `0x100F` |
//! | 12, 16 | `dwHeight`, `dwWidth` | `n`, `n` |
//! | 20 | `dwPitchOrLinearSize` | bytes per row, `n × 4` (f16) or `n × 8` (f32) |
//! | 24, 28 | `dwDepth`, `dwMipMapCount` | 0, 0 (one level) |
//! | 32–75 | `dwReserved1[11]` | 0 |
//! | 76 | `ddspf.dwSize` | 32 |
//! | 80 | `ddspf.dwFlags` | `DDPF_FOURCC` = 4 |
//! | 84 | `ddspf.dwFourCC` | `"DX10"`: a `DDS_HEADER_DXT10` follows |
//! | 88–107 | bit count and masks | 0 |
//! | 108 | `dwCaps` | `DDSCAPS_TEXTURE` = `0x1000` |
//! | 112–127 | `dwCaps2..4`, `dwReserved2` | 0 |
//! | 128 | `dxgiFormat` | 34 `R16G16_FLOAT` or 16 `R32G32_FLOAT` |
//! | 132 | `resourceDimension` | 3 (`TEXTURE2D`) |
//! | 136, 140, 144 | `miscFlag`, `arraySize`, `miscFlags2` | 0, 1, 0 |
//! | 148 | texels | rows top (first in memory) to bottom, each texel R then G |

/// `DXGI_FORMAT_R32G32_FLOAT`.
pub const DXGI_R32G32_FLOAT: u32 = 16;
/// `DXGI_FORMAT_R16G16_FLOAT`.
pub const DXGI_R16G16_FLOAT: u32 = 34;
/// Bytes before the first texel.
pub const HEADER_LEN: usize = 148;

/// Bytes per texel of a two-channel format.
#[must_use]
pub fn texel_bytes(dxgi_format: u32) -> usize {
    if dxgi_format == DXGI_R16G16_FLOAT {
        4
    } else {
        8
    }
}

/// The 148-byte header of a `width × height` two-channel texture of `dxgi_format`.
#[must_use]
pub fn header(width: u32, height: u32, dxgi_format: u32) -> Vec<u8> {
    let pitch = width * texel_bytes(dxgi_format) as u32;
    let mut w: Vec<u32> = vec![0x2053_4444, 124, 0x100F, height, width, pitch, 0, 0];
    w.extend([0; 11]); // dwReserved1
    w.extend([32, 4, u32::from_le_bytes(*b"DX10"), 0, 0, 0, 0, 0]); // DDS_PIXELFORMAT
    w.extend([0x1000, 0, 0, 0, 0]); // caps, reserved2
    w.extend([dxgi_format, 3, 0, 1, 0]); // DDS_HEADER_DXT10
    let bytes: Vec<u8> = w.iter().flat_map(|x| x.to_le_bytes()).collect();
    debug_assert_eq!(bytes.len(), HEADER_LEN);
    bytes
}

/// A parsed two-channel DDS texture.
#[derive(Debug)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// [`DXGI_R16G16_FLOAT`] or [`DXGI_R32G32_FLOAT`].
    pub dxgi_format: u32,
    /// The texel bytes (row-major, `width × height × texel_bytes`).
    pub data: Vec<u8>,
}

fn word(b: &[u8], offset: usize) -> u32 {
    u32::from_le_bytes([b[offset], b[offset + 1], b[offset + 2], b[offset + 3]])
}

/// Reads what [`header`] writes, checking every field listed in the module table.
///
/// # Errors
/// A message naming the first field that differs, or a length mismatch.
pub fn parse(bytes: &[u8]) -> Result<Texture, String> {
    if bytes.len() < HEADER_LEN {
        return Err(format!("{} bytes: shorter than the header", bytes.len()));
    }
    let expect = |offset: usize, want: u32, name: &str| {
        let got = word(bytes, offset);
        if got == want {
            Ok(())
        } else {
            Err(format!("{name} = {got:#x}, expected {want:#x}"))
        }
    };
    expect(0, 0x2053_4444, "magic")?;
    expect(4, 124, "dwSize")?;
    expect(8, 0x100F, "dwFlags")?;
    expect(76, 32, "ddspf.dwSize")?;
    expect(80, 4, "ddspf.dwFlags")?;
    expect(84, u32::from_le_bytes(*b"DX10"), "ddspf.dwFourCC")?;
    expect(108, 0x1000, "dwCaps")?;
    expect(132, 3, "resourceDimension")?;
    expect(140, 1, "arraySize")?;
    let (height, width, format) = (word(bytes, 12), word(bytes, 16), word(bytes, 128));
    if format != DXGI_R16G16_FLOAT && format != DXGI_R32G32_FLOAT {
        return Err(format!(
            "dxgiFormat {format}: not R16G16_FLOAT or R32G32_FLOAT"
        ));
    }
    expect(
        20,
        width * texel_bytes(format) as u32,
        "dwPitchOrLinearSize",
    )?;
    let len = width as usize * height as usize * texel_bytes(format);
    if bytes.len() != HEADER_LEN + len {
        return Err(format!(
            "{} bytes, expected {}",
            bytes.len(),
            HEADER_LEN + len
        ));
    }
    Ok(Texture {
        width,
        height,
        dxgi_format: format,
        data: bytes[HEADER_LEN..].to_vec(),
    })
}
