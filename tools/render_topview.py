#!/usr/bin/env python3
"""Top view of a grainstorm HDF5 snapshot coloured by particle marker: the picture
a camera far above the bed would take (seed paper Figs. 5-6), one colour per marker.

    render_topview.py SNAPSHOT.h5 -o top.png [--size 1024] [--extent X0 X1 Y0 Y1]
    render_topview.py RUN_DIR --step 20000 -o top.png     # particles_0000020000.h5 in RUN_DIR

Each pixel shows the marker of the particle whose surface is highest there (the
largest coordinate along the view axis): particles are spheres seen along the
axis, drawn as disks of their radius when they span pixels and as single points
when they are smaller than a pixel. The snapshot is read in chunks and splatted
into a depth buffer, so memory stays bounded at tens of millions of particles.
The layout read is docs/OUTPUT.md's (`particles/position`, `radius`, `marker`);
checkpoints hold the same datasets and render too. Needs numpy, h5py, matplotlib.
"""
import argparse
import glob
import os
import sys

import numpy as np

from topview_raster import DepthBuffer, Grid, Occlusion

# Rows read from the file at a time: 1 Mi rows of position, radius and marker are
# about 30 MB, plus the buffers below.
DEFAULT_CHUNK = 1 << 20
# The depth buffer holds 10 bytes a pixel: 2.7 GB at 16384 x 16384.
MAX_SIZE = 16384
DEFAULT_COLOURS = {0: "#1f5fbf", 1: "#f0640f"}  # blue and orange-red, as in the docs
# Further markers cycle through matplotlib's tab10 without its blue and orange.
EXTRA_COLOURS = ["tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:gray", "tab:olive", "tab:cyan"]

# Viewing axis -> (horizontal axis, its sign, vertical axis, depth axis), seen from
# the axis's positive side, so that the picture is what a camera on that side sees,
# not its mirror image: from +z, x runs right and y up; side views keep z up.
# From the negative side (--reverse) the horizontal axis and the depth turn round.
VIEWS = {"z": (0, +1, 1, 2), "x": (1, +1, 2, 0), "y": (0, -1, 2, 1)}


class InputError(Exception):
    """Bad input: the message says what and where; main() exits non-zero with it."""


def parse_arguments(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n", 1)[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("input", help="snapshot particles_<step>.h5 (or a checkpoint), or a run directory")
    p.add_argument("-o", "--output", required=True, help="PNG file to write")
    p.add_argument("--step", type=int, help="in a run directory: the snapshot of this step (default: the newest)")
    p.add_argument("--size", type=int, default=1024, help="pixels along the longer side of the image (default 1024)")
    p.add_argument("--extent", type=float, nargs=4, metavar=("H0", "H1", "V0", "V1"),
                   help="ranges [m] of the horizontal and vertical world axes in view (x, y along z; y, z along x; "
                        "x, z along y); default: the particles' bounding box, disks included")
    p.add_argument("--axis", choices=sorted(VIEWS), default="z",
                   help="look along this axis from its positive side; default z, from above")
    p.add_argument("--reverse", action="store_true", help="look from the axis's negative side (z: from below)")
    p.add_argument("--color", action="append", default=[], metavar="MARKER=COLOUR",
                   help="colour of a marker, a matplotlib colour name or #rrggbb (repeatable); "
                        "defaults: 0 blue, 1 orange-red")
    p.add_argument("--background", default="white", help="colour where no particle is (default white)")
    p.add_argument("--chunk", type=int, default=DEFAULT_CHUNK, help="particles read at a time (default 1048576)")
    p.add_argument("--no-culling", action="store_true",
                   help="draw every particle, hidden or not (slower; the picture is the same)")
    args = p.parse_args(argv)
    if not 1 <= args.size <= MAX_SIZE:
        p.error(f"--size must be 1 to {MAX_SIZE} pixels")
    if args.chunk < 1:
        p.error("--chunk must be at least 1")
    return args


def snapshot_path(source, step):
    """The snapshot file: `source` itself, or one of the particles_*.h5 in a run directory."""
    if os.path.isdir(source):
        if step is not None:
            path = os.path.join(source, f"particles_{step:010d}.h5")
            if not os.path.isfile(path):
                raise InputError(f"{source}: no snapshot of step {step} ({os.path.basename(path)})")
            return path
        found = sorted(glob.glob(os.path.join(source, "particles_*.h5")))
        if not found:
            raise InputError(f"{source}: no HDF5 snapshots (particles_*.h5); was the run's output.format hdf5?")
        return found[-1]
    if not os.path.exists(source):
        raise InputError(f"{source}: no such file or directory")
    if step is not None:
        raise InputError(f"--step picks a snapshot in a run directory; {source} is a file, which holds one snapshot")
    return source


def particle_datasets(f, path):
    """position, radius and marker of the file, checked for shape; InputError names what is wrong."""
    if "particles" not in f:
        raise InputError(f"{path}: no group 'particles'; not a grainstorm snapshot or checkpoint")
    group = f["particles"]
    missing = [name for name in ("position", "radius", "marker") if name not in group]
    if missing:
        have = " ".join(sorted(group.keys())) or "none"
        raise InputError(f"{path}: missing dataset {', '.join('particles/' + m for m in missing)} (the file has: "
                         f"{have}); write snapshots with these fields (scene key output.fields)")
    position, radius, marker = group["position"], group["radius"], group["marker"]
    n = position.shape[0] if position.ndim == 2 else -1
    if position.ndim != 2 or position.shape[1] != 3:
        raise InputError(f"{path}: particles/position has shape {position.shape}, expected (N, 3)")
    for name, ds in (("radius", radius), ("marker", marker)):
        if ds.shape != (n,):
            raise InputError(f"{path}: particles/{name} has shape {ds.shape}, expected ({n},) like position")
    if not np.issubdtype(marker.dtype, np.integer):
        raise InputError(f"{path}: particles/marker has type {marker.dtype}, expected integers")
    if n == 0:
        raise InputError(f"{path}: the snapshot holds no particles (particles/position is empty): nothing to draw")
    return position, radius, marker


def chunks(datasets, rows):
    """(position, radius, marker) blocks of at most `rows` particles, read one block at a time."""
    position, radius, marker = datasets
    for start in range(0, position.shape[0], rows):
        stop = min(start + rows, position.shape[0])
        yield (np.asarray(position[start:stop], dtype=np.float64), np.asarray(radius[start:stop], dtype=np.float64),
               np.asarray(marker[start:stop]))


def view_of(axis, reverse):
    """(horizontal axis, its sign, vertical axis, depth axis, depth sign) of a view."""
    h_axis, h_sign, v_axis, d_axis = VIEWS[axis]
    turn = -1 if reverse else +1
    return h_axis, turn * h_sign, v_axis, d_axis, turn


def view_coordinates(position, view):
    """Horizontal, vertical and depth (towards the camera) coordinates [m] of the centres."""
    h_axis, h_sign, v_axis, d_axis, d_sign = view
    return h_sign * position[:, h_axis], position[:, v_axis], d_sign * position[:, d_axis]


def survey(path, datasets, view, rows, need_box):
    """Smallest and largest radius [m] and, when asked, the extent in view
    coordinates that holds every particle's whole disk."""
    position, radius, _ = datasets
    lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
    r_min, r_max = np.inf, -np.inf
    for start in range(0, position.shape[0], rows):
        r = np.asarray(radius[start:start + rows], dtype=np.float64)
        r_min, r_max = min(r_min, r.min()), max(r_max, r.max())
        if need_box:
            centres = np.asarray(position[start:start + rows], dtype=np.float64)
            if not np.isfinite(centres).all():
                raise InputError(f"{path}: particles/position holds non-finite values (rows from {start}); "
                                 "give --extent to draw the others")
            h, v, _ = view_coordinates(centres, view)
            lo = np.minimum(lo, [np.min(h - r), np.min(v - r)])
            hi = np.maximum(hi, [np.max(h + r), np.max(v + r)])
    if not (np.isfinite(r_min) and r_min >= 0):
        raise InputError(f"{path}: particles/radius holds {r_min:g}; radii must be finite and not negative")
    return (r_min, r_max), (lo[0], hi[0], lo[1], hi[1]) if need_box else None


def extent_in_view(extent, view):
    """--extent gives world ranges; a mirrored horizontal axis turns its range round."""
    h0, h1, v0, v1 = extent
    if not (h1 > h0 and v1 > v0):
        raise InputError(f"--extent {h0:g} {h1:g} {v0:g} {v1:g}: each range must have its maximum above its minimum")
    return (h0, h1, v0, v1) if view[1] > 0 else (-h1, -h0, v0, v1)


def palette(options, background):
    """RGB (0-255) for markers 0..255 and for 'no particle' at index 256."""
    from matplotlib.colors import to_rgb
    colours = {m: EXTRA_COLOURS[(m - 2) % len(EXTRA_COLOURS)] for m in range(2, 256)}
    colours.update(DEFAULT_COLOURS)
    for option in options:
        marker, _, colour = option.partition("=")
        if not marker.strip().isdigit() or not 0 <= int(marker) <= 255 or not colour:
            raise InputError(f"--color {option}: expected MARKER=COLOUR with a marker 0..255, e.g. 1=red")
        colours[int(marker)] = colour
    table = np.zeros((257, 3), dtype=np.uint8)
    for marker, colour in list(colours.items()) + [(256, background)]:
        try:
            table[marker] = np.round(np.array(to_rgb(colour)) * 255)
        except ValueError:
            raise InputError(f"colour '{colour}' is not a matplotlib colour (a name such as 'red', or #rrggbb)")
    return table


def write_png(path, markers, table):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.imsave(path, table[np.where(markers < 0, 256, markers)], format="png")


def summary(path, output, buffer, count, time, step):
    g, marker = buffer.grid, buffer.marker
    covered = marker[marker >= 0]
    shares = ", ".join(f"marker {m}: {100.0 * c / len(covered):.1f} %" for m, c in
                       enumerate(np.bincount(covered)) if c) if len(covered) else "none"
    when = f", t = {time:g} s, step {step}" if time is not None else ""
    return (f"{output}: {g.width} x {g.height} px, {g.cell:.3g} m per pixel, {count} particles from {path}{when} "
            f"({buffer.drawn} drawn, the others hidden or out of view); "
            f"pixels covered {100.0 * len(covered) / marker.size:.1f} % ({shares})")


def particle_views(path, datasets, view, rows):
    """Per chunk: view coordinates, depth, radius [m] and marker. Particles whose
    position is not finite (a run that blew up) are left out: they are nowhere."""
    for position, radius, marker in chunks(datasets, rows):
        if marker.dtype != np.uint8 and len(marker) and (marker.min() < 0 or marker.max() > 255):
            raise InputError(f"{path}: particles/marker holds {marker.min()} to {marker.max()}; markers are 0..255")
        finite = np.isfinite(position).all(axis=1)
        if not finite.all():
            position, radius, marker = position[finite], radius[finite], marker[finite]
        yield view_coordinates(position, view) + (radius, marker)


def splat(path, datasets, view, image, radius_range, args):
    """The depth buffer of the whole snapshot; with disks of several pixels, a
    first pass maps where particles are hidden and the second skips those."""
    occlusion = None
    if Occlusion.pays_off(image, radius_range) and not args.no_culling:
        occlusion = Occlusion(image, radius_range)
        for h, v, depth, radius, _ in particle_views(path, datasets, view, args.chunk):
            occlusion.add(h, v, depth, radius)
    buffer = DepthBuffer(image)
    for h, v, depth, radius, marker in particle_views(path, datasets, view, args.chunk):
        if occlusion is not None:
            keep = occlusion.visible(h, v, depth, radius)
            h, v, depth, radius, marker = h[keep], v[keep], depth[keep], radius[keep], marker[keep]
        buffer.add(h, v, depth, radius, marker)
    return buffer


def render(args):
    import h5py
    path = snapshot_path(args.input, args.step)
    view = view_of(args.axis, args.reverse)
    # Bad colours or an output nowhere to go fail before the long read.
    table = palette(args.color, args.background)
    directory = os.path.dirname(os.path.abspath(args.output))
    if not os.path.isdir(directory):
        raise InputError(f"{args.output}: directory {directory} does not exist")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise InputError(f"{path}: cannot be read as HDF5 ({e})")
    with f:
        datasets = particle_datasets(f, path)
        radius_range, box = survey(path, datasets, view, args.chunk, need_box=args.extent is None)
        extent = extent_in_view(args.extent, view) if args.extent else box
        if not (extent[1] > extent[0] or extent[3] > extent[2]):
            raise InputError(f"{path}: the particles have no size and all stand at one point; give --extent")
        image = Grid.for_image(extent, args.size)
        buffer = splat(path, datasets, view, image, radius_range, args)
        time, step = f.attrs.get("time"), f.attrs.get("step")
        count = datasets[0].shape[0]
    write_png(args.output, buffer.markers(), table)
    print(summary(path, args.output, buffer, count, time, step))


def main(argv=None):
    args = parse_arguments(sys.argv[1:] if argv is None else argv)
    try:
        render(args)
    except InputError as e:
        print(f"render_topview: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
