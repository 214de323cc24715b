"""Run by scripts/flip_fixtures.sh inside its throwaway virtual environment: makes the image pairs,
runs flip-evaluator (NVIDIA's FLIP) on them, writes crates/caustics/tests/fixtures/flip/.

    python flip_fixtures.py WORK OUT FLIP_VERSION NUMPY_VERSION

WORK holds the renders (exact/receiver.exr, shah/receiver.exr, eye_shah/final.png,
eye_wd/final.png). Every input is written first and read back, so the reference sees exactly
the values committed: linear RGB as little-endian half floats (.f16), 8-bit sRGB codes (.srgb8).
"""
import sys

import numpy as np
import flip_evaluator as flip

work, out, flip_version, numpy_version = sys.argv[1:5]
W = H = 48


def exr_text(path, key):
    """A string attribute of an EXR header: name, NUL, "string", NUL, length (u32 LE), value."""
    data = open(path, "rb").read(1 << 16)
    tag = key.encode() + b"\0string\0"
    at = data.index(tag) + len(tag)
    size = int.from_bytes(data[at:at + 4], "little")
    return data[at + 4:at + 4 + size].decode()


def load(path):
    """RGB of an EXR's main layer (tinyexr) or of a PNG (k / 255), HxWx3 float32, row 0 on top."""
    img = np.asarray(flip.load(path), dtype=np.float32)[:, :, :3]
    assert img.shape == (H, W, 3), (path, img.shape)
    return img


def write_f16(name, rgb):
    """Writes linear RGB as half floats and returns what was written, as float32."""
    half = np.ascontiguousarray(rgb, dtype="<f2")
    assert np.all(np.isfinite(half)) and np.all(half >= 0), name
    half.tofile(f"{out}/{name}")
    return np.fromfile(f"{out}/{name}", dtype="<f2").reshape(H, W, 3).astype(np.float32)


def write_srgb8(name, codes):
    """Writes 8-bit codes (given as numbers 0..255) and returns what the reference reads: k / 255."""
    codes = np.rint(np.asarray(codes, dtype=np.float64))
    assert codes.min() >= 0 and codes.max() <= 255, name
    codes = np.ascontiguousarray(codes, dtype=np.uint8)
    codes.tofile(f"{out}/{name}")
    return np.fromfile(f"{out}/{name}", dtype=np.uint8).reshape(H, W, 3).astype(np.float32) / np.float32(255)


def shift(img, dx, dy):
    """The image moved dx texels right and dy down, the vacated border repeating the edge."""
    padded = np.pad(img, ((dy, 0), (dx, 0), (0, 0)), mode="edge")
    return padded[:H, :W]


exact = load(f"{work}/exact/receiver.exr")
commit = exr_text(f"{work}/exact/receiver.exr", "causticlab:commit")
render = load(f"{work}/shah/receiver.exr")
rng = np.random.default_rng(51)
noise = rng.standard_normal((H, W, 1)).astype(np.float32)
lum = 0.2126 * exact[..., 0] + 0.7152 * exact[..., 1] + 0.0722 * exact[..., 2]
hdr_ref = exact * np.array([1.0, 0.8, 0.55], np.float32) * np.float32(1.7)
hdr_test = hdr_ref.copy()
hdr_test[lum > 3.0, 2] *= 1.6          # the caustic too blue
hdr_test[40, 8] = [50.0, 50.0, 50.0]   # a firefly on the dim floor
ramp_t = (np.arange(H * W, dtype=np.float64) / (H * W - 1)).reshape(H, W)
ramp = np.stack([np.zeros_like(ramp_t), 255 * (1 - ramp_t), 255 * ramp_t], axis=-1).round()
green = np.broadcast_to(np.array([0, 255, 0], np.float64), (H, W, 3))

# name, kind, reference (file, values), test (file, values), parameters, what it is
pairs = []
exact_in = ("exact.f16", write_f16("exact.f16", exact))
pairs.append(("render", "hdr", exact_in, ("render.f16", write_f16("render.f16", render)), {},
              "shah (512^2 photons) receiver map E/E0 against the exact CPU reference (4M photons)"))
pairs.append(("shifted", "hdr", exact_in, ("shifted.f16", write_f16("shifted.f16", shift(exact, 2, 1))), {},
              "the exact caustic moved 2 texels right and 1 down (edge repeated)"))
noisy = np.maximum(exact * (1 + np.float32(0.3) * noise), 0)
pairs.append(("noisy", "hdr", exact_in, ("noisy.f16", write_f16("noisy.f16", noisy)),
              {"ppd": 40.0, "startExposure": -3.5, "stopExposure": 2.0},
              "the exact caustic times 1 + 0.3 N(0,1) per texel (seed 51), at 40 ppd over given exposures"))
pairs.append(("hdr", "hdr", ("hdr_ref.f16", write_f16("hdr_ref.f16", hdr_ref)),
              ("hdr_test.f16", write_f16("hdr_test.f16", hdr_test)), {},
              "the exact caustic tinted (1, 0.8, 0.55) x 1.7 (up to 50), the test's caustic blue x 1.6 and a firefly of 50"))
pairs.append(("eye", "ldr", ("eye_shah.srgb8", write_srgb8("eye_shah.srgb8", load(f"{work}/eye_shah/final.png") * 255)),
              ("eye_wd.srgb8", write_srgb8("eye_wd.srgb8", load(f"{work}/eye_wd/final.png") * 255)), {},
              "the eye view's final.png (sRGB) by wd-points (256^2 photons) against shah (512^2)"))
pairs.append(("ramp", "ldr", ("green.srgb8", write_srgb8("green.srgb8", green)),
              ("ramp.srgb8", write_srgb8("ramp.srgb8", ramp)), {"ppd": 20.0},
              "synthetic: green against green-to-blue in raster order, at 20 ppd, spanning the colour map"))

lines = [
    "# Written by scripts/flip_fixtures.sh (scripts/flip_fixtures.py): do not edit.",
    f'flip_evaluator = "{flip_version}"',
    f'numpy = "{numpy_version}"',
    f'renders_commit = "{commit}"',
    f"width = {W}",
    f"height = {H}",
]
magma = {}
for name, kind, (ref_file, ref), (test_file, test), params, what in pairs:
    ldr = kind == "ldr"
    args = dict(inputsRGB=ldr, parameters=dict(params))
    err, mean, used = flip.evaluate(ref, test, kind.upper(), applyMagma=False, **args)
    coloured, mean_again, _ = flip.evaluate(ref, test, kind.upper(), applyMagma=True, **args)
    assert mean == mean_again
    err = np.asarray(err, dtype=np.float32)[:, :, 0]
    err.astype("<f4").tofile(f"{out}/{name}.map.f32")
    coloured = np.asarray(coloured, dtype=np.float32)
    for y, x in np.ndindex(H, W):
        magma.setdefault(tuple(float(c) for c in coloured[y, x]), float(err[y, x]))
    lines += ["", "[[pair]]", f'name = "{name}"', f'what = "{what}"', f'kind = "{kind}"',
              f'reference = "{ref_file}"', f'test = "{test_file}"', f"ppd = {used['ppd']!r}",
              f"ppd_given = {str('ppd' in params).lower()}", f"mean = {float(mean)!r}", f'map = "{name}.map.f32"']
    if not ldr:
        given = "startExposure" in params
        lines += [f'exposures = "{"given" if given else "auto"}"', f"start_exposure = {used['startExposure']!r}",
                  f"stop_exposure = {used['stopExposure']!r}", f"exposure_count = {used['numExposures']}"]
    print(f"{name:8} {kind} ppd {used['ppd']:.4f} mean {mean:.6f}"
          + ("" if ldr else f" exposures {used['startExposure']:.4f}..{used['stopExposure']:.4f} x{used['numExposures']}"))

# Top-level keys go before the first [[pair]] table.
head, tables = lines[:6], lines[6:]
head += ["", "# The reference's magma output, one [error, R, G, B] per distinct colour it gave (any pair).",
         "magma = ["]
head += [f"  [{v!r}, {c[0]!r}, {c[1]!r}, {c[2]!r}]," for c, v in sorted(magma.items(), key=lambda kv: kv[1])]
lines = head + ["]"] + tables
with open(f"{out}/manifest.toml", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"{len(magma)} of the 256 magma entries seen")
