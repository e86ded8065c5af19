"""Self-gravity on the mesh: ``∇²Φ = 4πGρ`` by FFT in the shearing box (thesis §4.5).

The density (gas, or particles deposited with the drag's assignment function, TSC by default)
lives at cell centres of one block; :class:`PoissonSolver` returns the potential there and the
acceleration ``-∇Φ`` by centred differences, which the particle module gathers with the same
assignment function (Hockney & Eastwood 1981, §5-3: the same kernel both ways, with an even
Green's function and an odd difference operator, makes the mesh force of a pair antisymmetric,
so self-gravity exerts no net force -- momentum is conserved to round-off). Strength in code
units: ``4πG = G̃ = 4πGρ_g0/Ω²`` (Simon et al. 2016; :mod:`dustygas.physics.gravity`).

Boundaries (per axis)
---------------------
* **periodic** x, y, z: ``Φ̂ = -4πG ρ̂ / k²``, the mean density removed (Jeans' swindle).
* **shear-periodic** x: the radial images slide by ``s = qΩL_x t`` in y, ``ρ(x + L_x, y) =
  ρ(x, y + s)``. Along y the density is transformed first; each y-mode ``k_y`` of column ``i``
  is multiplied by ``exp(-i k_y s i Δx / L_x)``, which makes it periodic in x (the transform in
  the sheared frame; Gammie 2001 for the shearing sheet, Johansen et al. 2007 in the Pencil
  Code); the x transform then gives modes of radial wavenumber
  ``k_x = k_x' + k_y s / L_x`` -- the time-dependent wavenumber of a shearing wave, reduced to
  the mesh's band ``(-π/Δx, π/Δx)``, i.e. the wavenumber the sampled field actually has.
  The phase is a continuous shift: for any ``s`` it is exact for a density resolved by the
  mesh (no Nyquist content), so a sheared sinusoid gets its analytic potential to round-off
  at any shift. The alternative, Athena++'s: remap the density to the last time the box was periodic by an interpolation between the two
  bracketing integer cell shifts, solve periodically, and remap back -- adds an interpolation
  error ``O(Δy²)`` at non-integer shifts (and smooths the grid scale twice per solve); it
  cannot meet 1e-12 and costs two remaps instead of two multiplications. Chosen: the phase.
  Ghost columns of ``Φ`` come from the same modes, so ``Φ(x ± L_x, y) = Φ(x, y ± s)`` exactly.
* **vacuum** z (isolated above and below, with (shear-)periodic x, y): each horizontal mode
  ``k = |k_⊥|`` is convolved in z with ``-2πG e^{-k|z|}/k`` (``2πG|z|`` for ``k = 0``), the
  kernel averaged over each source cell; this is the convolution that domain doubling
  (Hockney & Eastwood 1981, §6-5) does with FFTs of length ``2 n_z``, done here in ``O(n_z)``
  per mode by two recursive sweeps. With ``n_z = 1`` the block is a razor-thin sheet of surface
  density ``Σ`` and ``Φ̂ = -2πG Σ̂ / k`` in its plane (Toomre 1964).
* **vacuum** in all three axes: an isolated system, domain doubling with the cell-integrated
  Green's function ``-G ∫_cell dV'/|x - x'|`` (:mod:`dustygas.grid.gravity.isolated`).

Nyquist modes (the y mode ``π/Δy``, and the x and z modes at ``±π/Δ``) are dropped: they have
no sign, and keeping the set of modes symmetric under ``k -> -k`` is what keeps the potential
real and the net force zero.

Under MPI (a later issue)
-------------------------
The domain is split into x or y slabs (a settled dust layer is thin in z, so z is never split
for load balance). Planned: a **slab (pencil-free) transpose through mpi4py's Alltoall(v)**
around these same serial scipy FFTs -- transform y and z locally on x-slabs, Alltoall to
y-slabs, transform x (with the shear phase, which needs the column index ``i`` only), apply
the Green's function, and back. Why not ``mpi4py-fft``: it needs FFTW built and found at
install time (a system library our pure-PyPI install cannot provide portably), it would be a
second FFT implementation whose round-off differs from the serial path's (we want rank-count
invariance, bit for bit, with the serial solve), and it offers pencil decompositions we do not
need while the ranks are fewer than the cells of one axis. The transpose is a small layer on
top of this module and keeps every kernel here unchanged.

Modules
-------
poisson
    :class:`PoissonSolver`, :func:`potential`, :func:`acceleration`.
kernels
    The compiled Green's-function multiplications, vertical vacuum sweeps and gradient.
isolated
    The integrated Green's function of an isolated system.
"""

from .poisson import GRAVITY_BOUNDARIES, PoissonSolver, acceleration, potential

__all__ = ["GRAVITY_BOUNDARIES", "PoissonSolver", "acceleration", "potential"]
