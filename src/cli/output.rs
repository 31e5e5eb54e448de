//! Where `render` writes its image: checked before any rendering (a format the encoder
//! knows, a folder that exists), then written whole or not at all.

use std::path::Path;

use super::CliError;

/// The image format `path`'s extension asks for: PNG or JPEG. A usage error otherwise,
/// or when the folder it names does not exist, before any time is spent rendering.
pub fn check_output(path: &Path) -> Result<image::ImageFormat, CliError> {
    let format = match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase) {
        Some(e) if e == "png" => image::ImageFormat::Png,
        Some(e) if e == "jpg" || e == "jpeg" => image::ImageFormat::Jpeg,
        _ => {
            return Err(CliError::Usage(format!(
                "{}: the output must be a .png, .jpg or .jpeg file",
                path.display()
            )));
        }
    };
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !folder.is_dir() {
        return Err(CliError::Usage(format!(
            "{}: the folder {} does not exist",
            path.display(),
            folder.display()
        )));
    }
    Ok(format)
}

/// Encodes `image` as `format` (JPEG without the alpha channel it cannot hold) and writes
/// it atomically: a failure leaves no partial file and an existing one as it was.
pub fn write_image(path: &Path, image: &image::RgbaImage, format: image::ImageFormat) -> Result<(), CliError> {
    let mut bytes = Vec::new();
    let encoded = match format {
        image::ImageFormat::Jpeg => image::DynamicImage::ImageRgba8(image.clone())
            .to_rgb8()
            .write_to(&mut std::io::Cursor::new(&mut bytes), format),
        _ => image.write_to(&mut std::io::Cursor::new(&mut bytes), format),
    };
    encoded.map_err(|source| CliError::WriteImage {
        path: path.to_path_buf(),
        source,
    })?;
    lightpaint::project::replace_atomically(path, &bytes).map_err(|e| CliError::WriteImage {
        path: path.to_path_buf(),
        source: image::ImageError::IoError(e),
    })
}
