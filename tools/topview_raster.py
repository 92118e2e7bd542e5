"""Drawing spheres seen along an axis into a depth buffer, for tools/render_topview.py:
disks rasterised in vectorised batches of bounded size, and an occlusion map that
skips particles that cannot show. Lengths are in metres unless said otherwise."""
import numpy as np

# Fragments (pixel, depth, particle) made at once; about 80 bytes each in flight.
FRAGMENT_BUDGET = 1 << 20


class Grid:
    """Square cells over the view: origin (h0, v0) [m] at the bottom-left corner,
    `cell` [m] wide, `width` x `height` cells; cell (row 0, column 0) is bottom left."""

    def __init__(self, h0, v0, cell, width, height):
        self.h0, self.v0, self.cell, self.width, self.height = h0, v0, cell, width, height

    @staticmethod
    def for_image(extent, size):
        h0, h1, v0, v1 = extent
        pixel = max(h1 - h0, v1 - v0) / size  # square pixels [m]
        if not pixel > 0:
            raise ValueError(f"empty extent {extent}")
        return Grid(h0, v0, pixel, max(1, int(round((h1 - h0) / pixel))), max(1, int(round((v1 - v0) / pixel))))

    def coarser(self, factor):
        """The grid of factor x factor blocks of this one's cells, covering it."""
        return Grid(self.h0, self.v0, self.cell * factor, -(-self.width // factor), -(-self.height // factor))

    def cells(self, h, v, radius):
        """Centres and radii in cell units."""
        return (h - self.h0) / self.cell, (v - self.v0) / self.cell, radius / self.cell


def disk_fragments(grid, x, y, r, depth, inside):
    """(cell index, surface height, particle index) of the cells disks cover, at most
    FRAGMENT_BUDGET at a time. x, y, r in cell units; depth [m] of the centres.
    A cell counts when its centre lies in the disk; the cell holding the disk's
    centre always counts, so a particle smaller than a cell still shows (point
    splatting) and none falls between cell centres. With `inside`, a cell counts
    only when it lies wholly in the disk, and its height is the sphere's lowest
    over it: a lower bound of what any cell centre there will show."""
    # Cells that can count are at most r + 1/2 from the cell holding the centre.
    half_width = np.floor(r + 0.5).astype(np.int64)
    for k in np.unique(half_width):
        which = np.flatnonzero(half_width == k)
        offset = np.arange(-k, k + 1)
        dx, dy = (a.ravel() for a in np.meshgrid(offset, offset))
        if len(dx) > FRAGMENT_BUDGET:  # a disk wider than the budget: its cells in bands of rows
            for i in which:
                yield from large_disk_fragments(grid, x[i], y[i], r[i], depth[i], i, int(k), inside)
            continue
        batch = max(1, FRAGMENT_BUDGET // len(dx))
        for s in range(0, len(which), batch):
            p = which[s:s + batch]
            column = np.floor(x[p]).astype(np.int64)[:, None] + dx
            row = np.floor(y[p]).astype(np.int64)[:, None] + dy
            yield cover(grid, x[p, None], y[p, None], r[p, None], depth[p, None], p[:, None], column, row,
                        (dx == 0) & (dy == 0), inside)


def large_disk_fragments(grid, x, y, r, depth, i, k, inside):
    """disk_fragments of particle i alone, clipped to the grid, in bands of rows."""
    cx, cy = int(np.floor(x)), int(np.floor(y))
    columns = np.arange(max(cx - k, 0), min(cx + k + 1, grid.width))
    rows_per_band = max(1, FRAGMENT_BUDGET // max(1, len(columns)))
    for band in range(max(cy - k, 0), min(cy + k + 1, grid.height), rows_per_band):
        rows = np.arange(band, min(band + rows_per_band, cy + k + 1, grid.height))
        column, row = (a.ravel() for a in np.meshgrid(columns, rows))
        yield cover(grid, x, y, r, depth, i, column, row, (column == cx) & (row == cy), inside)


def cover(grid, x, y, r, depth, particle, column, row, centre, inside):
    """The fragments of disks (x, y, r) over cells (column, row), arrays that broadcast."""
    if inside:  # the farthest corner decides
        far_x = np.maximum(np.abs(column - x), np.abs(column + 1 - x))
        far_y = np.maximum(np.abs(row - y), np.abs(row + 1 - y))
        squared = r * r - (far_x ** 2 + far_y ** 2)
        covered = squared >= 0
    else:
        squared = r * r - ((column + 0.5 - x) ** 2 + (row + 0.5 - y) ** 2)
        covered = (squared >= 0) | centre
    covered &= (column >= 0) & (column < grid.width) & (row >= 0) & (row < grid.height)
    surface = depth + grid.cell * np.sqrt(np.maximum(squared, 0.0))
    return ((row * grid.width + column)[covered], surface[covered],
            np.broadcast_to(particle, covered.shape)[covered])


class DepthBuffer:
    """Per cell the highest surface seen so far [m] and the marker it belongs to (-1: none)."""

    def __init__(self, grid, inside=False):
        self.grid, self.inside = grid, inside
        self.depth = np.full(grid.width * grid.height, -np.inf)
        self.marker = np.full(grid.width * grid.height, -1, dtype=np.int16)
        self.drawn = 0  # particles splatted

    def add(self, h, v, depth, radius, marker):
        """Splats a chunk of particles: view coordinates, depths and radii in metres."""
        x, y, r = self.grid.cells(h, v, radius)
        touches = (x + r >= 0) & (x - r < self.grid.width) & (y + r >= 0) & (y - r < self.grid.height)
        x, y, r, depth, marker = x[touches], y[touches], r[touches], depth[touches], marker[touches]
        self.drawn += len(x)
        for cell, surface, particle in disk_fragments(self.grid, x, y, r, depth, self.inside):
            np.maximum.at(self.depth, cell, surface)
            # Where two fragments are exactly as high, either marker is right.
            top = surface == self.depth[cell]
            self.marker[cell[top]] = marker[particle[top]]

    def markers(self):
        """Marker per cell as an image, row 0 at the top."""
        return self.marker.reshape(self.grid.height, self.grid.width)[::-1]


class Occlusion:
    """Culls particles that cannot show: a coarse map of lower bounds of the visible
    surface, built in a first pass, tells that a particle's top (centre + radius)
    lies below everything its disk could cover. In a bed many layers deep most
    particles are hidden, and each costs (2r + 1)^2 fragments otherwise."""

    def __init__(self, image, radius_range):
        self.pixel = image.cell
        # Blocks small enough that every disk covers some of them wholly.
        self.factor = max(1, int(radius_range[0] / image.cell / 2))
        self.map = DepthBuffer(image.coarser(self.factor), inside=True)
        self.floors = {}  # reach [blocks] -> per block, the lowest bound within that reach of it

    @staticmethod
    def pays_off(image, radius_range):
        return radius_range[0] / image.cell >= 2  # else disks span few pixels: culling costs what it saves

    def add(self, h, v, depth, radius):
        self.map.add(h, v, depth, radius, np.zeros(len(h), dtype=np.int16))

    def floor(self, reach):
        if reach not in self.floors:
            g = self.map.grid
            bound = self.map.depth.reshape(g.height, g.width)
            self.floors[reach] = sliding_minimum(sliding_minimum(bound, reach, 0), reach, 1)
        return self.floors[reach]

    def visible(self, h, v, depth, radius):
        g = self.map.grid
        column, row = np.floor((h - g.h0) / g.cell).astype(np.int64), np.floor((v - g.v0) / g.cell).astype(np.int64)
        # The pixel centres a disk covers lie within max(r, sqrt(2)/2) pixels of its
        # centre (the centre's own pixel always counts), so in blocks at most this
        # many rows and columns away from the centre's block.
        reach = np.floor((radius / self.pixel + 0.71) / self.factor).astype(np.int64) + 1
        keep = np.ones(len(h), dtype=bool)  # centres beyond the image are kept
        inside = (column >= 0) & (column < g.width) & (row >= 0) & (row < g.height)
        for k in np.unique(reach[inside]):
            p = np.flatnonzero(inside & (reach == k))
            keep[p] = depth[p] + radius[p] >= self.floor(int(k))[row[p], column[p]]
        return keep


def sliding_minimum(a, reach, axis):
    """Minimum over the window of +-reach along `axis` (+inf beyond the array: no
    pixel there to hide), by doubling windows: log(reach) passes, not reach."""
    a = np.moveaxis(a, axis, 0)
    n, window = a.shape[0], 2 * reach + 1
    m = np.concatenate([np.full((reach,) + a.shape[1:], np.inf), a, np.full((reach,) + a.shape[1:], np.inf)])
    span = 1  # m[i] is the minimum of the padded rows i .. i + span - 1
    while 2 * span <= window:
        m = np.minimum(m[:-span], m[span:])
        span *= 2
    out = np.minimum(m[:n], m[window - span:window - span + n])
    return np.moveaxis(out, 0, axis)
