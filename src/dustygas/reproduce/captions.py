"""Captions of the thesis's computational figures, keyed by figure number (copied from the thesis text).

The gallery (:mod:`dustygas.reproduce.gallery`) places each figure beside its caption; a figure
registered as exactly ``figN.M`` gets caption ``N.M`` unless it declares its own; variants
(``fig4.3-settling``) and figures that are not the thesis's declare theirs.
Mathematics is written in Unicode (τ_s, μ ≡ ρ_d/ρ_g), otherwise the text is the thesis's.
"""

from __future__ import annotations

__all__ = ["THESIS_CAPTIONS"]

#: thesis figure number -> caption
THESIS_CAPTIONS: dict[str, str] = {
    "1.10": (
        'Maximum dust particle density present in the simulation in Figure 1.11 as a function of the elapsed '
        'simulation time. The simulation begins with drag and vertical gravity turned on at t = -10T_orb '
        '(where T_orb is the orbital period). Initially, the maximum dust to gas density ratio is near 1%. '
        'The streaming instability creates overdense regions that saturate at max(ρ_p/ρ_gas) ~ 50, and when '
        'self-gravity is activated, the maximum observed density increases dramatically. Reproduced from '
        'Johansen et al. (2007) with permission.'
    ),
    "1.13": (
        'Particle scale heights over time for the simulations in Figure 1.12. This figure is reproduced from '
        'Bai and Stone (2010b) with permission. The colours represent different grain sizes, and going from '
        'largest to smallest follow the order: black, green, blue, pink, cyan, yellow, red. Data from the 2D '
        'simulations are represented by solid lines, data from the 3D are represented by the dashed lines. '
        'The labels Z1, Z2, and Z3 in the simulation naming convention refers to dust to gas mass ratios of '
        '1%, 2%, and 3%, respectively.'
    ),
    "3.1": (
        'Radial profiles for s_frag and s_drift in the initial conditions of the simulated protoplanetary '
        'disks studied by Gonzalez et al. (2017), reproduced with permission. The top panel is for a flat '
        'disk, where the surface density does not change with radius, and the bottom panel is for a disk '
        'where the surface density scales with r^-1 .'
    ),
    "3.2": (
        'Vertical distribution of dust mass fraction ϵ from the dust settling test. The results using the '
        'upwinding scheme (equation 3.17) are in the left panels, and the results from the arithmetic average'
        ' scheme (3.4) are in the right panels. The numbers inset in each panel represent the elapsed time in'
        ' the simulation in units of the Keplerian orbital period. The data for the vertical position of the '
        'dust is in units of the vertical gas scale height.'
    ),
    "3.3": (
        'Conservation of dust mass mε in the upwinding and arithmetic average scheme. The y -axis represents '
        'the total sum of all the dust mass in the simulation, scaled by the total dust mass in the initial '
        'condition.'
    ),
    "3.5": (
        'Velocity of the radial drift of dust particles as described by equation 3.23, results match Figure '
        '4.2 from Armitage (2013). Here we use η = 7.5 × 10^-3 and v_r,gas/v_K = -3.75 × 10^-5. The dashed '
        'line is the value for v_r,gas/v_K, and is provided to show that radial velocity the dust tracks the '
        'radial velocity of the gas for small τ_s .'
    ),
    "3.6": (
        'Evolution of the dust particle position in the x - y plane for the radial drift test with a 1,000 '
        'particle dust ring. Two different sizes of grains were tested, one with a size that gives τ_s = 1 '
        '(left) and one with τ_s = 10 (right).'
    ),
    "3.7": (
        'Averaged radial velocity of the dust particles in the τ_s = 1 dust ring radial drift test as a '
        'function of elapsed time in the simulation, in units of the Keplerian orbital period, where this '
        'period is computed using the average radial position of the particles.'
    ),
    "3.8": (
        'Averaged radial position of the dust particles in the τ_s = 1 dust ring radial drift test as a '
        'function of elapsed time in the simulation, in units of the Keplerian orbital period, where this '
        'period is computed using the average radial position of the particles.'
    ),
    "3.9": (
        'Velocity dispersion, σ_v , in units of the azimuthal Keplerian velocity, v_k , in the radial drift '
        'ring test. The top frame is for the τ_s = 1 test, and the bottom frame is for the τ_s = 10 test. The'
        ' different coloured lines represent a different component of the velocity, and the dashed and solid '
        'lines represent the data for the gas and dust fluids, respectively. The analytically predicted dust '
        'radial velocity from equation 3.23 is given by the grey dashed line.'
    ),
    "3.10": (
        'Random walk of gaseous SPH particles in the radial and vertical direction in a simulated '
        'protoplanetary disk. The numbers represented in the upper-left corner of each panel represent the '
        'elapsed time in the simulation, in units of the Keplerian orbital period, where this orbital period '
        "is calculated for each of the separate panels/particles individually, according to the particles' "
        'initial radial position. The initial particle positions are given by the black dots, the path the '
        'particle random walks is given by the red dotted line, the final position is given by the red dot, '
        'and the grey lines represent the vertical disk scale heights.'
    ),
    "3.11": (
        'Position of the SPH particles in the rotational (x-y) plane of the disk for the high resolution disk'
        ' with particle splitting (left) and the original, unsplit disk (right). Only particles near the disk'
        ' midplane (within one smoothing length of z = 0) are shown.'
    ),
    "3.12": (
        'A histogram comparing the particle spacing, binned by midplane radius (r_xy), in the high resolution'
        ' disk with particle splitting and the original, unsplit disk. The separation is estimated as l = '
        '(mρ)^(1/3), and the value on the y -axis the ratio of l in the unsplit disk to the split disk, '
        'l_u/l_s .'
    ),
    "3.13": (
        'Averaged radial velocity of the dust particles in the τ_s = 1 dust ring radial drift test, where the'
        ' results for the higher resolution disk and the original, lower resolution disk are both shown. The '
        'x -axis represents the of elapsed time in the simulation, in units of the Keplerian orbital period, '
        'where this period is computed using the average radial position of the particles.'
    ),
    "3.14": (
        'Averaged radial position of the τ_s = 1 dust particles in the dust ring radial drift test, where the'
        ' results for the higher resolution disk and the original, lower resolution disk are both shown. The '
        'time axis is in units of the Keplerian orbital period.'
    ),
    "3.15": (
        'Time evolution of the standard deviation of the radial velocity of the dust particles in the τ_s = 1'
        ' dust ring radial drift test, where the results for the higher resolution disk and the original, '
        'lower resolution disk are both shown. The time axis is in units of the Keplerian orbital period.'
    ),
    "3.16": (
        'Time evolution of the standard deviation of the radial position of the dust particles in the τ_s = 1'
        ' dust ring radial drift test, where the results for the higher resolution disk and the original, '
        'lower resolution disk are both shown. The time axis is in units of the Keplerian orbital period.'
    ),
    "4.1": (
        'Left. Growth rates, s , of the linear wave perturbation amplitudes due to the fastest growing mode '
        'of the streaming instability. Note, the growth rates are scaled by a factor 2π/Ω. The growth rates '
        'are marked by the contours, and the parameter space being explored are the dust properties: μ ≡ '
        'ρ_d/ρ_g on the x -axis, and τ_s on the y -axis. Right. The value of k_x which produces the fastest '
        'growing mode according to the same parameter space as the left panel, when k_z is fixed at a '
        'particular value. From Youdin and Goodman (2005), reproduced with permission.'
    ),
    "4.2": (
        'Growth rates of the linear wave perturbation amplitudes due to the fastest growing mode of the '
        'streaming instability. Here, the angle between the perturbation wave vector components is fixed at '
        'θ_k ≡ tan⁻¹(k_x/k_z) = 30°. The magnitude of the wave vector is plotted on the x -axis, with '
        'the growth rate s of the fastest growing mode plotted on the y -axis. A range of systems with '
        'various values of τ_s and μ are considered. These results match Squire and Hopkins (2018).'
    ),
    "4.3": (
        'Growth rates of the linear wave perturbation amplitudes due to the fastest growing mode of the '
        'streaming instability, as in Figure 4.2. However, this analysis was completed including a vertical '
        'component to the steady-state background dust velocity according to equation 4.19. These results '
        'match Squire and Hopkins (2018).'
    ),
    "4.6": (
        'Confirmation of the enhanced growth rates of the linear wave perturbation amplitudes from numerical '
        'simulations. Crosses mark the numerical results from a 2-D (r - z) periodic box.'
    ),
    "4.7": (
        'Distribution of dust in a high-resolution 3-D simulation of dust and gas in shearing box generated '
        'using the Athena astrophysics code. Dust particles are coloured by the dust density. The number of '
        'grid points in x , y and z are 256, 256 and 384, respectively, and 1.8×10^7 dust particles are used.'
        ' Only particles within the vicinity of the midplane (|z| < 0.03) are shown in the middle square, and'
        ' the particles that are shown on the boundaries of the domain, on top of the white mesh, are the '
        'particles within a similar tolerance of each boundary. Note that the true domain of the simulation '
        'extends to ± 0.15H_g in z , but only ± 0.10H_g is shown in z . A dust to gas mass ratio of μ = 0.03 '
        'is used, and the dust grain size is such that τ_s = 1. The radial pressure gradient for the gas is '
        'represented by η v_K = 0.05 (see equation 3.24). The time inset in the top right corner is in units '
        'of the orbital period.'
    ),
    "4.8": (
        'Distribution of dust from the same simulation in Figure 4.7, but only positions in the r - θ (x - y)'
        ' plane and with |z| < 0.03 are shown. The time inset in the top right corner is in units of the '
        'orbital period.'
    ),
    "4.9": (
        'Distribution of dust from the same simulation in Figure 4.7, but only positions in the r - z (x - z)'
        ' plane and with |θ| < 0.03 are shown. The time inset in the top right corner is in units of the '
        'orbital period.'
    ),
    "4.10": (
        'Distribution of dust surface density from the same simulation in Figure 4.7 and the 2-D FFT of the '
        'surface density. The left panels represent the vertically integrated dust surface density Σ_d in the'
        ' x - y plane of the simulation, and the right panels represent the magnitude of the 2-D FFT of Σ_d '
        'in the k_x - k_y plane. The time inset is in units of the orbital period.'
    ),
}
