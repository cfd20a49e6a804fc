"""rotor_chain.Network against a numpy implementation written here, separately: the compatibility
matrix of a patch built from the cell's description, counts by a dense SVD with the issue's rank
rule, the winding of det Q(k) by following its phase on a fine path."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

import rotor_chain as rc

SQ3 = math.sqrt(3.0)


def kl_cell(x1, x2, x3, z):
    """Kane and Lubensky's deformed kagome as keyword arguments (their eqs. in the text of
    arXiv:1308.0554: d1 = a1/2 + s2, d2 = a2/2 - s1, d3 = a3/2)."""
    a = [np.array([math.cos(2 * math.pi * p / 3), math.sin(2 * math.pi * p / 3)]) for p in range(3)]
    x = [x1, x2, x3]
    s = []
    for p in range(3):
        prev, nxt = (p + 2) % 3, (p + 1) % 3
        y = z / 3 + x[prev] - x[nxt]
        s.append(x[p] * (a[prev] - a[nxt]) + y * a[p])
    d = [a[0] / 2 + s[1], a[1] / 2 - s[0], a[2] / 2]
    nodes = [{"name": f"d{i + 1}", "kind": "joint", "position": list(map(float, d[i]))} for i in range(3)]
    bonds = [
        {"from": "d1", "to": "d3", "cell": [1, 1]},
        {"from": "d2", "to": "d3", "cell": [1, 1]},
        {"from": "d2", "to": "d1", "cell": [-1, 0]},
        {"from": "d3", "to": "d1", "cell": [-1, 0]},
        {"from": "d3", "to": "d2", "cell": [0, -1]},
        {"from": "d1", "to": "d2", "cell": [0, -1]},
    ]
    return {"dimension": 2, "lattice": [list(a[0]), list(a[1])], "nodes": nodes, "bonds": bonds}


def chain_cell(theta_bar, r=0.8):
    return {
        "dimension": 1,
        "lattice": [[2.0, 0.0]],
        "nodes": [
            {"name": "up", "kind": "rotor", "pivot": [0.0, 0.0], "length": r, "angle": math.pi / 2 - theta_bar},
            {"name": "down", "kind": "rotor", "pivot": [1.0, 0.0], "length": r, "angle": -math.pi / 2 + theta_bar},
        ],
        "bonds": [{"from": "up", "to": "down", "cell": [0]}, {"from": "down", "to": "up", "cell": [1]}],
    }


SQUARE = {
    "dimension": 2,
    "lattice": [[1.0, 0.0], [0.0, 1.0]],
    "nodes": [{"name": "a", "kind": "joint", "position": [0.0, 0.0]}],
    "bonds": [{"from": "a", "to": "a", "cell": [1, 0]}, {"from": "a", "to": "a", "cell": [0, 1]}],
}


class Reference:
    """The cell's geometry and compatibility matrices, in numpy."""

    def __init__(self, d):
        self.dim = d["dimension"]
        self.lattice = np.array(d["lattice"], dtype=float)
        self.names = [n["name"] for n in d["nodes"]]
        self.points, self.dirs = [], []
        for n in d["nodes"]:
            if n["kind"] == "joint":
                self.points.append(np.array(n["position"], float))
                self.dirs.append([np.array([1.0, 0.0]), np.array([0.0, 1.0])])
            else:
                phi, r = n["angle"], n["length"]
                self.points.append(np.array(n["pivot"], float) + r * np.array([math.cos(phi), math.sin(phi)]))
                self.dirs.append([np.array([-math.sin(phi), math.cos(phi)])])
        self.offsets = np.cumsum([0] + [len(x) for x in self.dirs])
        self.dof = int(self.offsets[-1])
        self.bonds = []
        for b in d["bonds"]:
            cell = list(b.get("cell", [0] * self.dim)) + [0] * (2 - self.dim)
            f, t = self.names.index(b["from"]), self.names.index(b["to"])
            shift = sum(c * self.lattice[i] for i, c in enumerate(cell[: self.dim]))
            v = self.points[t] + shift - self.points[f]
            self.bonds.append((f, t, cell, v / np.linalg.norm(v)))

    def bloch(self, theta):
        q = np.zeros((len(self.bonds), self.dof), complex)
        for row, (f, t, cell, e) in enumerate(self.bonds):
            phase = np.exp(1j * (cell[0] * theta[0] + cell[1] * theta[1]))
            for j, dvec in enumerate(self.dirs[f]):
                q[row, self.offsets[f] + j] -= e @ dvec
            for j, dvec in enumerate(self.dirs[t]):
                q[row, self.offsets[t] + j] += phase * (e @ dvec)
        return q

    def patch(self, n1, n2, periodic):
        rows = []
        ncell = n1 * n2
        for c2 in range(n2):
            for c1 in range(n1):
                for f, t, cell, e in self.bonds:
                    t1, t2 = c1 + cell[0], c2 + cell[1]
                    if periodic:
                        t1, t2 = t1 % n1, t2 % n2
                    elif not (0 <= t1 < n1 and 0 <= t2 < n2):
                        continue
                    row = np.zeros(ncell * self.dof)
                    base_f = (c1 + n1 * c2) * self.dof
                    base_t = (t1 + n1 * t2) * self.dof
                    for j, dvec in enumerate(self.dirs[f]):
                        row[base_f + self.offsets[f] + j] -= e @ dvec
                    for j, dvec in enumerate(self.dirs[t]):
                        row[base_t + self.offsets[t] + j] += e @ dvec
                    rows.append(row)
        return np.array(rows)


def svd_counts(c):
    s = np.linalg.svd(c, compute_uv=False)
    rank = int(np.sum(s > 1e-9 * s[0])) if s.size else 0
    return c.shape[1] - rank, c.shape[0] - rank


def winding_of(ref, direction, transverse, samples=20000):
    t = np.linspace(0.0, 2 * math.pi, samples + 1)
    dets = []
    for x in t:
        theta = [transverse, transverse]
        theta[direction] = x
        if ref.dim == 1:
            theta[1] = 0.0
        dets.append(np.linalg.det(ref.bloch(theta)))
    phase = np.unwrap(np.angle(np.array(dets)))
    return int(round((phase[-1] - phase[0]) / (2 * math.pi)))


CELLS = {
    "kagome": kl_cell(0, 0, 0, 0),
    "twisted": kl_cell(0.08, 0.08, 0.08, 0),
    "polarized": kl_cell(0.1, 0.1, -0.1, 0),
    "tilted": kl_cell(-0.05, 0.05, 0.05, 0.02),
    "square": SQUARE,
}


@pytest.mark.parametrize("name", sorted(CELLS))
def test_counts_match_a_dense_numpy_svd(name):
    d = CELLS[name]
    net, ref = rc.Network(**d), Reference(d)
    for n1, n2 in [(3, 3), (4, 3), (5, 5)]:
        for boundary, periodic in [("periodic", True), ("free", False)]:
            got = net.counts((n1, n2), boundary)
            c = ref.patch(n1, n2, periodic)
            assert (got["zero_modes"], got["self_stresses"]) == svd_counts(c), (n1, n2, boundary)
            assert got["zero_modes"] - got["self_stresses"] == got["dof"] - got["bonds"]
        assert np.allclose(net.compatibility((n1, n2), "free"), ref.patch(n1, n2, False), atol=1e-13)


def test_bloch_matrix_and_null_spaces():
    d = CELLS["tilted"]
    net, ref = rc.Network(**d), Reference(d)
    theta = [0.7, -1.3]
    assert np.allclose(net.bloch(theta), ref.bloch(theta), atol=1e-14)
    modes, stresses = net.null_spaces((4, 4), "periodic")
    c = ref.patch(4, 4, True)
    assert modes.shape == (c.shape[1], 2) and stresses.shape == (c.shape[0], 2)
    assert np.abs(c @ modes).max() < 1e-12 and np.abs(c.T @ stresses).max() < 1e-12
    w = net.frequencies(theta)
    d_matrix = ref.bloch(theta).conj().T @ ref.bloch(theta)
    assert np.allclose(np.sort(w), np.sqrt(np.clip(np.linalg.eigvalsh(d_matrix), 0, None)), atol=1e-12)


@pytest.mark.parametrize("name,expected", [("twisted", [0, 0]), ("polarized", [1, 1]), ("tilted", [-1, 0])])
def test_winding_and_polarization_against_numpy(name, expected):
    d = CELLS[name]
    net, ref = rc.Network(**d), Reference(d)
    w = net.winding()
    for i in range(2):
        assert w["winding"][i] == winding_of(ref, i, 0.81)
    # Kane and Lubensky eq. 11 in (a1, a2) coordinates; the standard cell has r0 = 0.
    assert np.allclose(w["polarization"], expected, atol=1e-9)
    assert np.allclose(w["dipole"], 0.0, atol=1e-12)


def test_the_chain_winds_by_its_lean_and_its_end_mode_follows():
    for theta_bar in (0.58, -0.58):
        d = chain_cell(theta_bar)
        net, ref = rc.Network(**d), Reference(d)
        n = net.winding()["winding"][0]
        assert n == winding_of(ref, 0, 0.0) and n in (0, 1)
        strip = net.strip(1, 20)
        expected = {"low": 1, "high": 0} if n == 1 else {"low": 0, "high": 1}
        assert strip["edge_zero_modes"] == expected
        assert svd_counts(ref.patch(20, 1, False)) == (1, 0)


def test_strip_edges_of_a_polarized_lattice():
    net = rc.Network.ready("deformed-kagome", 0.1, 0.1, -0.1, 0.0)
    s = net.strip(1, 24)
    assert s["edge_zero_modes"] == {"low": 1, "high": 3}
    assert s["predicted"] == {"low": 1, "high": 3}
    assert s["modes"].shape[1] == 4


def test_guest_modes_and_ready_cells():
    count, strains = rc.Network(**SQUARE).guest_modes()
    assert count == 1 and abs(abs(strains[0, 0, 1]) - math.sqrt(0.5)) < 1e-12
    assert rc.Network.ready("kagome").guest_modes()[0] == 0
    chain = rc.Network.ready("paper-chain-left")
    assert chain.dimension == 1 and chain.dof == 2 and chain.bond_count == 2


def test_strings_files_and_pickles(tmp_path):
    net = rc.Network(**CELLS["tilted"])
    text = net.to_toml()
    again = rc.Network.from_string(text)
    path = tmp_path / "cell.toml"
    path.write_text(text)
    assert rc.Network.from_file(path).to_toml() == text == again.to_toml()
    assert pickle.loads(pickle.dumps(net)).to_toml() == text
    dist, freq = net.bands("G-X-M-G", 20)
    assert dist.shape == (58,) and freq.shape == (58, 6)


def test_errors_carry_keys_lines_and_numbers():
    bad = 'dimension = 2\nlattice = [[1.0, 0.0], [0.0, 1.0]]\n[[node]]\nname = "a"\nkind = "joint"\nposition = [0, 0]\n[[bond]]\nfrom = "a"\nto = "b"\n'
    with pytest.raises(rc.CellError) as info:
        rc.Network.from_string(bad)
    e = info.value
    assert e.variant == "UnknownNode" and e.key == "bond[0].to" and e.line == 9 and e.suggestion == "a"
    assert isinstance(e, ValueError)
    with pytest.raises(rc.CellError) as info:
        rc.Network(dimension=2, lattice=[[1, 0], [0, 1]], nodes=[{"name": "a", "kind": "joint"}])
    assert info.value.variant == "Missing" and info.value.key == "node[0].position" and info.value.line is None
    with pytest.raises(ValueError, match="unknown key 'mass'"):
        rc.Network(dimension=2, lattice=[[1, 0], [0, 1]], nodes=[{"name": "a", "kind": "joint", "position": [0, 0], "mass": 1}])
    with pytest.raises(rc.NetworkError) as info:
        rc.Network.ready("kagome").winding()
    assert info.value.variant == "WindingUndefined" and info.value.direction == 1
    with pytest.raises(rc.NetworkError) as info:
        rc.Network.ready("kagome").counts((2, 5), "periodic")
    assert info.value.variant == "PatchSize" and info.value.found == 2
