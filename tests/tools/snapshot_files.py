"""Writes HDF5 snapshots in the layout of grainstorm's writer (src/io/h5_snapshot.cpp,
src/io/h5_walls.cpp, docs/OUTPUT.md), for tests of the Python tools without a run:
the same groups, dataset names, shapes and little-endian types, fixed-length
null-terminated string attributes, contiguous (unchunked) datasets."""
import h5py
import numpy as np

# Name, file type and units of every particle field, in the writer's order (snapshot_fields.cpp).
FIELDS = [
    ("id", "<u4", "1"), ("material", "u1", "1"), ("marker", "u1", "1"), ("radius", "<f4", "m"),
    ("mass", "<f4", "kg"), ("inertia", "<f4", "kg m^2"), ("position", "<f8", "m"), ("velocity", "<f8", "m/s"),
    ("angular_velocity", "<f8", "rad/s"), ("orientation", "<f4", "1 (unit quaternion w, x, y, z)"),
    ("force", "<f8", "N"), ("torque", "<f8", "N m"), ("contact_count", "<u2", "1"),
]
COLUMNS = {"position": 3, "velocity": 3, "angular_velocity": 3, "orientation": 4, "force": 3, "torque": 3}
DEFAULT_FIELDS = ("id", "material", "marker", "radius", "position", "velocity", "angular_velocity")
WALL_VEC3 = ("point", "normal", "velocity", "angular_velocity", "axis_point", "shift", "current_point",
             "current_normal")


def string_attribute(obj, name, value):
    """As h5::write_string_attribute: H5T_C_S1 of the text's length + 1, NULLTERM."""
    type_id = h5py.h5t.C_S1.copy()
    type_id.set_size(len(value.encode()) + 1)
    type_id.set_strpad(h5py.h5t.STR_NULLTERM)
    obj.attrs.create(name, np.array(value.encode(), dtype=f"S{len(value.encode()) + 1}"),
                     dtype=h5py.Datatype(type_id))


def root_attributes(f, count, fields, time, step):
    string_attribute(f, "kind", "grainstorm snapshot")
    f.attrs.create("format_version", 1, dtype="<i4")
    string_attribute(f, "grainstorm_version", "0.1.0")
    f.attrs.create("time", time, dtype="<f8")
    f.attrs.create("step", step, dtype="<i8")
    f.attrs.create("scene_hash", 0x5C1F0E7A9D3B2C41, dtype="<u8")
    string_attribute(f, "scene", "synthetic.yaml")
    f.attrs.create("particle_count", count, dtype="<i8")
    string_attribute(f, "fields", " ".join(fields))
    string_attribute(f, "units", "SI: m, kg, s, N, rad")


def field_data(name, dtype, n, given):
    """The data given for a field, or zeros (id: 0..N-1) of the field's shape."""
    shape = (n, COLUMNS[name]) if name in COLUMNS else (n,)
    if name in given:
        data = np.asarray(given[name]).astype(dtype)
        assert data.shape == shape, f"{name}: shape {data.shape}, expected {shape}"
        return data
    return np.arange(n, dtype=dtype) if name == "id" else np.zeros(shape, dtype=dtype)


def empty_walls(f):
    """A snapshot of a scene without analytic walls still has the group, with W = 0 rows."""
    g = f.create_group("walls")
    g.attrs.create("count", 0, dtype="<i8")
    string_attribute(g, "kinds", "0 plane, 1 disk, 2 cylinder")
    for name in ("kind", "material"):
        g.create_dataset(name, shape=(0,), dtype="<i4")
    for name in ("radius", "length"):
        g.create_dataset(name, shape=(0,), dtype="<f8")
    for name in WALL_VEC3:
        g.create_dataset(name, shape=(0, 3), dtype="<f8")
    g.create_dataset("rotation", shape=(0, 3, 3), dtype="<f8")


def write_snapshot(path, position, radius=None, marker=None, fields=DEFAULT_FIELDS, time=0.5, step=5000, **more):
    """particles_<step>.h5 content at `path`: position (N, 3) [m], radius (N) [m], marker (N);
    fields not given are zeros. Leave a name out of `fields` to write a file without it."""
    position = np.asarray(position, dtype=np.float64).reshape(-1, 3)
    n = len(position)
    given = dict(more, position=position)
    if radius is not None:
        given["radius"] = np.broadcast_to(np.asarray(radius, dtype=np.float64), (n,))
    if marker is not None:
        given["marker"] = np.broadcast_to(np.asarray(marker), (n,))
    chosen = [name for name, _, _ in FIELDS if name in fields or name == "position"]
    with h5py.File(path, "w") as f:
        root_attributes(f, n, chosen, time, step)
        group = f.create_group("particles")
        for name, dtype, units in FIELDS:
            if name in chosen:
                ds = group.create_dataset(name, data=field_data(name, dtype, n, given))
                string_attribute(ds, "units", units)
        empty_walls(f)


def lattice_bed(lower, upper, spacing):
    """Centres of a simple cubic lattice filling the box [lower, upper] at `spacing`."""
    axes = [np.arange(lo, hi + 1e-12, spacing) for lo, hi in zip(lower, upper)]
    return np.stack([a.ravel() for a in np.meshgrid(*axes, indexing="ij")], axis=1)


def close_packed_bed(diameter, layers, width):
    """Centres of a face-centred cubic packing (ABC-stacked triangular layers) over
    [-width/2, width/2]^2 from z = 0 up: a bed in which, as in a settled one, each
    layer hides the gaps of the layers below."""
    row = diameter * np.sqrt(3) / 2
    shifts = [(0.0, 0.0), (diameter / 2, row / 3), (diameter, 2 * row / 3)]
    i, j = np.meshgrid(np.arange(int(width / diameter)), np.arange(int(width / row)), indexing="ij")
    layer = []
    for k in range(layers):
        dx, dy = shifts[k % 3]
        x = -width / 2 + (i + (j % 2) / 2) * diameter + dx
        y = -width / 2 + j * row + dy
        layer.append(np.stack([x.ravel(), y.ravel(), np.full(x.size, k * diameter * np.sqrt(2 / 3))], axis=1))
    return np.concatenate(layer)
