"""The checked, frozen model: plain data built by `cranefe.model.load`.

Indices refer to ``Model.node_names`` (nodes), ``Model.bodies`` (bodies; ``GROUND`` = -1
is the fixed frame) and ``Model.drums``. Coordinates are always 3-vectors; a planar model
(``plane: xz``) has y = 0 everywhere and motion only in the x-z plane.
"""

from dataclasses import dataclass, field, replace

import numpy as np

GROUND = -1

EFFECT_CHOICES = {
    "drive": ("coupled", "held", "reduced"),
    "damping": ("none", "modal", "exact"),
    "structure": ("rigid", "flexible"),
    "rope_mass_matrix": ("consistent", "lumped"),
}


@dataclass(frozen=True)
class Effects:
    """Which physics is on (model-format.md, "Effects")."""

    rope_elasticity: bool = True
    rope_mass: int = 0
    sway: bool = True
    drive: str = "coupled"
    damping: str = "none"
    structure: str = "rigid"
    rope_mass_matrix: str = "consistent"   # extension: mass matrix of rope elements

    def as_dict(self):
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class Body:
    name: str
    mass: float
    com: np.ndarray          # (3,)
    inertia: np.ndarray      # (3, 3) about the com, global axes
    nodes: tuple             # node indices carried rigidly


@dataclass(frozen=True)
class Joint:
    type: str                # fixed | hinge | ball | slider
    bodies: tuple            # (b1, b2) body indices, GROUND for the fixed frame
    at: int                  # node index
    axis: np.ndarray         # (3,) unit vector (hinge, slider), else None
    entry: str               # "joints[3]" for messages
    name: str = None         # optional name (operation scenes drive joints by name)
    range: np.ndarray = None  # (2,) travel from the reference: m (slider), rad (hinge)
    range_key: str = "range"  # how the file gives it: range | range_deg (for messages)

    @property
    def label(self):
        """The joint in messages: its name and entry (``'luffing' (joints[0])``)."""
        return f"'{self.name}' ({self.entry})" if self.name else self.entry

    @property
    def range_entry(self):
        """The entry of its range in the model file (``joints[2].range_deg``)."""
        return f"{self.entry}.{self.range_key}"


@dataclass(frozen=True)
class Spring:
    name: str
    type: str                # axial | rotational
    stiffness: float
    psi: float
    nodes: tuple = ()        # axial: (a, b)
    bodies: tuple = ()       # rotational: (b1, b2)
    at: int = -1             # rotational: node (informative)
    axis: np.ndarray = None  # rotational: unit vector


@dataclass(frozen=True)
class Drum:
    name: str
    node: int
    radius: float
    inertia: float           # drum and all that turns with it, at drum speed
    rotor_inertia: float     # at motor speed
    gear_ratio: float
    brake: bool
    rope_reserve: float = float("inf")   # m of rope on the drum that can be paid out
                                         #   beyond the reference state

    @property
    def reduced_inertia(self):
        """Drum plus motor rotor reduced to drum speed: J + J_rotor i^2."""
        return self.inertia + self.rotor_inertia * self.gear_ratio**2


@dataclass(frozen=True)
class Rope:
    """A rope expanded into spans (tackles already resolved)."""

    name: str
    EA: float
    mass_per_length: float
    psi: float
    extra_length: float
    span_a: np.ndarray       # (ns,) node index where each span starts
    span_b: np.ndarray       # (ns,) node index where it ends
    falls: np.ndarray        # (ns,) multiplicity of each span
    end_drums: tuple         # drum indices at the rope's ends (0, 1 or 2 entries)
    points: tuple            # the expanded point sequence, names (for reports)


@dataclass(frozen=True)
class Member:
    name: str
    type: str                # beam | truss
    nodes: tuple
    E: float
    A: float
    rho: float
    G: float = 0.0
    Iy: float = 0.0
    Iz: float = 0.0
    J: float = 0.0
    orientation: np.ndarray = None
    elements: int = 1
    mass: str = "consistent"
    psi: float = 0.0
    pairs: np.ndarray = None     # (k, 2) separate two-node pieces (extension), else None
    Asy: float = 0.0             # shear areas (Timoshenko beam); 0: no shear deformation
    Asz: float = 0.0
    releases: tuple = ()         # ((node, (local rotations 0=rx 1=ry 2=rz, ...)), ...)
    Wy: float = 0.0              # elastic section moduli for stresses; 0: not given
    Wz: float = 0.0

    @property
    def timoshenko(self):
        """Shear deformation and rotary inertia (shear areas given)."""
        return self.Asy > 0 or self.Asz > 0


@dataclass(frozen=True)
class LinearDrive:
    name: str
    nodes: tuple             # (A, C)
    pinion_radius: float
    gear_ratio: float
    rotor_inertia: float


@dataclass(frozen=True)
class Support:
    """Restrained directions of a node (model-format.md, "supports")."""

    node: int
    translations: np.ndarray  # (k, 3) unit directions whose displacement is zero
    rotations: np.ndarray     # (k, 3) unit axes whose rotation is zero
    entry: str                # "supports.A" for messages


@dataclass(frozen=True)
class PointMasses:
    nodes: np.ndarray        # (k,)
    mass: np.ndarray         # (k,)
    inertia: np.ndarray      # (k, 3, 3)


@dataclass(frozen=True)
class Model:
    name: str
    file: str
    text: str
    planar: bool
    gravity: np.ndarray
    node_names: tuple
    coords: np.ndarray       # (n, 3)
    ground: np.ndarray       # node indices
    masses: PointMasses
    bodies: tuple
    joints: tuple
    springs: tuple
    drums: tuple
    ropes: tuple
    members: tuple
    linear_drives: tuple
    effects: Effects
    analysis: dict = field(default_factory=dict)   # from a scene; {} for a model
    supports: tuple = ()                            # Support per supported node
    scene: str = None                               # scene name, if loaded from one
    scene_file: str = None                          # and its path

    @property
    def node_index(self):
        return {n: i for i, n in enumerate(self.node_names)}

    @property
    def length_scale(self):
        """Size of the model (m), for tolerances and scale factors."""
        span = np.ptp(self.coords, axis=0).max() if len(self.coords) else 0.0
        return float(span) if span > 0 else 1.0

    def with_effects(self, **changes):
        return replace(self, effects=replace(self.effects, **changes))
