"""The grid engine on one block of a decomposed mesh, with the run-loop protocol of the box.

:class:`DistributedGridEngine` holds one :class:`~dustygas.grid.engine.GridEngine` per rank on
its :class:`~.decomposition.BlockMesh` and runs the integrator stage by stage, calling the halo
exchange (:class:`~.halo.HaloExchange`) on each stage's input before the compiled stage (whose
own ghost fill then does the physical faces). The time step is the global minimum (an
exact ``max`` of the Courant rates, so it is the serial one).

Outputs and diagnostics are decomposition-independent by construction: the domain blocks are
gathered to rank 0 into a whole-box engine, whose :meth:`history`, :meth:`snapshot` and
:meth:`checkpoint` are those of a serial run of the same state (sums over the box in the
serial order). The checkpoint is the serial one (the whole conserved array and the budgets
per row), so a run written on ``N`` ranks restarts on ``M``. The boundary budgets (radial mass
flux, source y-momentum, mass lost through open z faces) are running totals per unit of cells
(:mod:`dustygas.grid.budget`: z planes, rows ``(k, j)``, face cells), each held and added to by
the one block that holds the unit, so the gathered units are the serial ones and so are their
sums, bit for bit -- but for a rotating box whose first swept axis (x) is split, where a row's
y-momentum is the sum of its blocks' parts (added in rank order).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import SimulationError, UserError
from ..grid.boundaries import NEIGHBOUR
from ..grid.budget import budget_offsets, budget_rows_from, budget_sections
from ..grid.engine import GridEngine
from ..grid.mesh import Mesh
from .decomposition import Decomposition, block_mesh, check_cuts, check_layout, choose_layout, unsplittable_axes
from .halo import HaloExchange

__all__ = ["DistributedGridEngine"]


class DistributedGridEngine:
    """Isothermal gas on ``mesh`` split over the ranks of ``comm`` (see module doc).

    Parameters
    ----------
    mesh
        The whole mesh.
    comm
        MPI communicator (default ``MPI.COMM_WORLD``).
    layout
        Ranks per axis ``(px, py, pz)``; None: :func:`~.decomposition.choose_layout`.
    z_cuts
        With ``layout``: the first row of every z block and ``nz`` (uneven blocks); None: equal blocks.
    **engine_options
        Keyword arguments of :class:`~dustygas.grid.engine.GridEngine`.
    """

    work_label = "zone-cycles"
    #: the run loop's sign that this engine spans the ranks (rank 0 writes, decisions are agreed)
    distributed = True

    def __init__(self, mesh: Mesh, comm=None, layout: tuple[int, int, int] | None = None,
                 z_cuts: tuple[int, ...] | None = None, **engine_options: Any):
        if comm is None:
            from .comm import world

            comm = world()
        self.comm = comm
        self.rank, self.size = comm.Get_rank(), comm.Get_size()
        boundaries = tuple(engine_options.get("boundaries", ("periodic", "periodic", "periodic")))
        forbidden = unsplittable_axes(boundaries, bool(engine_options.get("orbital_advection", False)), mesh.active)
        if engine_options.get("integrator", "vl2") == "ctu" and self.size > 1:
            raise UserError("scheme.integrator = 'ctu' does not run on several MPI ranks yet (use vl2)")
        if layout is None:
            dims = choose_layout(mesh.shape, self.size, forbidden, mesh.nghost)
        else:
            dims = tuple(int(p) for p in layout)
            if int(np.prod(dims)) != self.size:
                raise UserError(f"mpi layout {dims}: needs {int(np.prod(dims))} ranks, the run has {self.size}")
            if z_cuts is None:
                check_layout(mesh.shape, dims, forbidden, mesh.nghost)
            else:  # uneven z blocks: x and y as the layout says, z as the cuts say
                check_layout(mesh.shape[:2] + (dims[2] * mesh.nghost,), dims, forbidden, mesh.nghost)
                check_cuts(mesh.shape[2], dims[2], z_cuts, mesh.nghost)
        self.mesh = mesh
        self.decomposition = Decomposition(mesh.shape, dims, z_cuts)  # type: ignore[arg-type]
        self.block = block_mesh(mesh, self.decomposition, self.rank)
        self.local = GridEngine(self.block, **engine_options)
        wraps = tuple(k in ("periodic", "shear-periodic") or not on for k, on in zip(boundaries, mesh.active))
        self.halo = HaloExchange(comm, self.decomposition, self.rank, self.block.ghosts, wraps)  # type: ignore[arg-type]
        faces = {face: NEIGHBOUR for face, inner in self.halo.neighbour_faces().items() if inner}
        self.local._bc = self.local._bc._replace(**faces)
        # the budget sections of the open z faces that are block faces here (nothing leaves through them)
        self._inner_z_budget = [name for name, face in (("z_lower", "z_lo"), ("z_upper", "z_hi")) if face in faces]
        self.whole = GridEngine(mesh, **engine_options) if self.rank == 0 else None
        self.work_units = mesh.ncells

    # ------------------------------------------------------------------ state
    @property
    def t(self) -> float:
        return self.local.t

    @t.setter
    def t(self, value: float) -> None:
        self.local.t = value

    @property
    def cycle(self) -> int:
        return self.local.cycle

    @cycle.setter
    def cycle(self, value: int) -> None:
        self.local.cycle = value

    def _block(self, field: Any) -> np.ndarray:
        shape = tuple(reversed(self.mesh.shape))
        return np.broadcast_to(np.asarray(field, dtype=np.float64), shape)[self.decomposition.block_slices(self.rank)]

    def set_primitive(self, rho: Any = 1.0, vx: Any = 0.0, vy: Any = 0.0, vz: Any = 0.0) -> None:
        """Set the box from whole-box density and full velocities (each rank takes its block)."""
        self.local.set_primitive(self._block(rho), self._block(vx), self._block(vy), self._block(vz))

    def _gather(self) -> None:
        """Copy every block's domain cells and budget units into the whole-box engine on rank 0."""
        inner = (slice(None),) + self.block.interior()
        mine = np.ascontiguousarray(self.local.states[0][inner])
        blocks = self.comm.gather((mine, self.local.budget_rows.copy()), root=0)  # uneven z cuts: shapes differ
        if self.rank == 0:
            whole = self.whole.states[0][(slice(None),) + self.mesh.interior()]
            self.whole.budget_rows[:] = 0.0
            units = budget_sections(self.whole.budget_rows, self.mesh.shape)
            for r in range(self.size):  # rank order (a unit that several blocks hold: module doc)
                whole[(slice(None),) + self.decomposition.block_slices(r)] = blocks[r][0]
                for name, part in budget_sections(blocks[r][1], self.decomposition.block_shape_of(r)).items():
                    units[name][self._unit_slices(r)[name]] += part
            self.whole.t, self.whole.cycle = self.local.t, self.local.cycle

    def _unit_slices(self, rank: int) -> dict[str, tuple[slice, ...]]:
        """Where the budget sections of the block of ``rank`` lie in the whole box's
        (:func:`~dustygas.grid.budget.budget_sections`)."""
        zs, ys, xs = self.decomposition.block_slices(rank)
        return {"radial": (zs,), "y_source": (zs, ys), "z_lower": (ys, xs), "z_upper": (ys, xs)}

    # ------------------------------------------------------------------ run-loop protocol
    def agree(self, decisions: tuple) -> tuple:
        """The per-rank run-loop decisions (signal number, checkpoint-by-wall-clock, out of
        wall time) combined over the ranks: the largest signal number, and a flag set on any
        rank is set on all (collective)."""
        from mpi4py import MPI

        combined = np.zeros(len(decisions), dtype=np.int64)
        self.comm.Allreduce(np.array([int(d) for d in decisions], dtype=np.int64), combined, op=MPI.MAX)
        return (int(combined[0]),) + tuple(bool(c) for c in combined[1:])

    def timestep(self) -> float:
        """The serial time step: ``cfl / max`` over all blocks of the Courant rate."""
        from mpi4py import MPI

        local = self.local
        top = np.empty(2)
        self.comm.Allreduce(np.array([local._rate, 1.0 if local._bad >= 0 else 0.0]), top, op=MPI.MAX)
        rate = float(top[0])
        if top[1] > 0:
            if local._bad >= 0:
                try:
                    local.timestep()
                except SimulationError as exc:
                    i0, j0, k0 = self.block.offset
                    raise SimulationError(f"{exc} (block of rank {self.rank}, first cell i={i0}, j={j0}, k={k0})",
                                          state=exc.state) from None
            raise SimulationError(f"invalid gas state on another rank at time={local.t:.6g} cycle={local.cycle}")
        return local.cfl / rate

    def advance(self, dt: float) -> None:
        """One step: for each stage, the halo exchange of its input, then the compiled stage."""
        for s in range(self.local.stage_count):
            self.advance_stage(s, dt)

    def advance_stage(self, stage: int, dt: float, ext: np.ndarray | None = None, nthreads: int = 0) -> None:
        """:meth:`GridEngine.advance_stage <dustygas.grid.engine.GridEngine.advance_stage>` of the
        block (``ext``: the block's source), after the halo exchange of the stage's input."""
        local = self.local
        if stage == 0 and self._inner_z_budget:
            units = budget_sections(local.budget_rows, self.block.shape)
            self._kept = [units[name].copy() for name in self._inner_z_budget]
        self.halo.fill(local.stage_input(stage), local.stage_ghost_depth(stage))
        local.advance_stage(stage, dt, ext, nthreads)
        if stage == local.stage_count - 1 and self._inner_z_budget:
            units = budget_sections(local.budget_rows, self.block.shape)
            for name, kept in zip(self._inner_z_budget, self._kept):
                units[name][...] = kept  # the flux through a block face is not lost

    def history(self) -> dict[str, float]:
        """:meth:`GridEngine.history` of the gathered box (the same on every rank)."""
        self._gather()
        values = self.whole.history() if self.rank == 0 else None
        return self.comm.bcast(values, root=0)

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """The whole box on rank 0; empty on the other ranks (they write nothing)."""
        self._gather()
        return self.whole.snapshot() if self.rank == 0 else ({}, {})

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """The serial checkpoint of the whole box on rank 0 (restartable on any rank count)."""
        self._gather()
        return self.whole.checkpoint() if self.rank == 0 else ({}, {})

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        """Take this rank's block of a whole-box checkpoint (rank 0 keeps the budget)."""
        u = np.asarray(arrays["conserved"])
        want = (4,) + tuple(reversed(self.mesh.shape))
        if u.shape != want:
            raise UserError(f"checkpoint holds a state of shape {u.shape}, the configuration a {want}")
        mine = {"conserved": np.ascontiguousarray(u[(slice(None),) + self.decomposition.block_slices(self.rank)]),
                "budget_rows": self._budget_share(budget_rows_from(arrays, self.mesh.shape))}
        self.local.restore(mine, attrs)

    def _budget_share(self, rows: np.ndarray) -> np.ndarray:
        """This rank's units of the whole box's budget ``rows``: the z planes and rows of its
        block (a row along a split x axis to the first x block), the face cells of the lower and
        upper z faces to the blocks of those faces; they go on adding to them as one process would."""
        out = np.zeros(budget_offsets(*self.block.shape)[0])
        mine, whole = budget_sections(out, self.block.shape), budget_sections(rows, self.mesh.shape)
        cx, cy, cz = self.decomposition.coords(self.rank)
        owner = {"radial": cx == 0 and cy == 0, "y_source": cx == 0, "z_lower": cz == 0,
                 "z_upper": cz == self.decomposition.dims[2] - 1}
        for name, where in self._unit_slices(self.rank).items():
            if owner[name]:
                mine[name][...] = whole[name][where]
        return out

    def primitive(self) -> tuple[np.ndarray, ...]:
        """Whole-box density and full velocities on rank 0 (collective; None elsewhere)."""
        self._gather()
        return self.whole.primitive() if self.rank == 0 else None  # type: ignore[return-value]
