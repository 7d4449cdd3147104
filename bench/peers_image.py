"""Images for bench/peers.py: reading EXRs, the error metrics, the pixels
that see the light, PNG views. Reads and writes through Mitsuba's Bitmap
(scalar_rgb), which the benchmark needs anyway, and numpy."""
import numpy as np


def _mitsuba():
    import mitsuba as mi
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    return mi


def read(path):
    """An image as float64 rows x columns x 3 (RGB), row 0 at the top."""
    pixels = np.array(_mitsuba().Bitmap(str(path)), dtype=np.float64)
    if pixels.ndim != 3 or pixels.shape[2] < 3:
        raise ValueError(f"{path}: not an RGB image")
    return pixels[:, :, :3]


def errors(image, reference):
    """(MSE, relMSE) over pixels and channels, as `wavepath converge` defines
    them: mean of (x - r)^2 and of (x - r)^2 / (r^2 + 0.01)."""
    if image.shape != reference.shape:
        raise ValueError(f"image {image.shape} and reference {reference.shape} differ in size")
    squared = (image - reference) ** 2
    return float(squared.mean()), float((squared / (reference ** 2 + 0.01)).mean())


def light_pixels(image, radiance, tolerance=1e-3):
    """Pixels that see nothing but the light: every channel reads the radiance
    (within tolerance, relative) in the pixel and in its eight neighbours, so
    that a pixel on the light's edge, which a few samples happened to see
    whole, does not count."""
    at_light = np.all(np.abs(image / radiance - 1.0) <= tolerance, axis=2)
    inner = at_light.copy()
    inner[0, :] = inner[-1, :] = inner[:, 0] = inner[:, -1] = False
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            inner &= np.roll(np.roll(at_light, dy, axis=0), dx, axis=1)
    return inner


def block_means(image, blocks=4):
    """Per-channel means of a blocks x blocks grid (row 0 at the top), so that
    images with the same mean but not the same picture tell apart."""
    rows = np.array_split(np.arange(image.shape[0]), blocks)
    columns = np.array_split(np.arange(image.shape[1]), blocks)
    return np.array([[image[np.ix_(r, c)].reshape(-1, 3).mean(axis=0) for c in columns] for r in rows])


def write_row(images, path, scale=1 / 8.0):
    """The images side by side as one PNG view (write_png's)."""
    write_png(np.concatenate(images, axis=1), path, scale)


def triple(values):
    return " ".join(f"{v:.4f}" for v in values)


def write_png(image, path, scale=1 / 8.0):
    """A fixed view (the same exposure for every renderer, so views compare):
    linear x scale, gamma 1/2.2, clipped."""
    mi = _mitsuba()
    view = np.clip(image * scale, 0.0, 1.0) ** (1 / 2.2)
    mi.Bitmap((view * 255.0 + 0.5).astype(np.uint8)).write(str(path))


def mean_agreement(image, reference, blocks):
    """Per-channel mean differences of a blocks x blocks grid, image against
    reference: (z, relative deviation, relative sigma), each blocks x blocks
    x 3. sigma is the combined standard error of a block's mean difference,
    sqrt(sum of (x - r)^2) / pixels (pixels independent, so the squared
    difference estimates the sum of both pixels' variances where the
    expectations agree); z the difference over sigma."""
    rows = np.array_split(np.arange(image.shape[0]), blocks)
    columns = np.array_split(np.arange(image.shape[1]), blocks)
    z = np.zeros((blocks, blocks, 3))
    deviation = np.zeros((blocks, blocks, 3))
    sigma = np.zeros((blocks, blocks, 3))
    for i, r in enumerate(rows):
        for j, c in enumerate(columns):
            x = image[np.ix_(r, c)].reshape(-1, 3)
            y = reference[np.ix_(r, c)].reshape(-1, 3)
            difference = x.mean(axis=0) - y.mean(axis=0)
            error = np.sqrt(((x - y) ** 2).sum(axis=0)) / x.shape[0]
            scale = np.maximum(np.abs(y.mean(axis=0)), 1e-12)
            z[i, j] = np.where(error > 0, difference / np.maximum(error, 1e-300), 0.0)
            deviation[i, j] = difference / scale
            sigma[i, j] = error / scale
    return z, deviation, sigma

