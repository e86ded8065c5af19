"""The history's budget totals are the correctly rounded sums of their sections (math.fsum of every entry)."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from dustygas.grid.budget import budget_offsets, budget_sections, budget_totals

SHAPE = (4, 3, 2)  # nx, ny, nz: sections of 2, 6, 12 and 12 units

# finite values stay below 1e300 (twelve of them cannot overflow fsum's partials); +inf and NaN come
# alone (fsum refuses inf + -inf, as a run would never hold both)
entries = st.one_of(st.just(0.0), st.just(-0.0), st.floats(min_value=-1e300, max_value=1e300),
                    st.floats(min_value=-1e-300, max_value=1e-300), st.sampled_from([1e16, -1e16, 1.0, -1.0]),
                    st.sampled_from([math.inf, math.nan]))


@settings(max_examples=300, deadline=None)
@given(st.lists(entries, min_size=budget_offsets(*SHAPE)[0], max_size=budget_offsets(*SHAPE)[0]))
def test_each_total_is_the_fsum_of_all_its_units(values):
    """Zeros, signed zeros, cancelling 1e16s, tiny values, NaN and inf: bit for bit the fsum of the whole section."""
    rows = np.array(values)
    expected = [math.fsum(section.ravel()) for section in budget_sections(rows, SHAPE).values()]
    got = budget_totals(rows, SHAPE)
    for e, g in zip(expected, got):
        assert (math.isnan(e) and math.isnan(g)) or (e == g and math.copysign(1, e) == math.copysign(1, g))


def test_an_unused_section_of_zeros_sums_to_plus_zero():
    """A 2D x-y box's z-face sections hold only zeros (and -0.0 from a negated zero flux): +0.0, as fsum gives."""
    rows = np.zeros(budget_offsets(*SHAPE)[0])
    rows[-5:] = -0.0
    totals = budget_totals(rows, SHAPE)
    assert totals.tolist() == [0.0, 0.0, 0.0, 0.0]
    assert all(math.copysign(1, t) == 1 for t in totals)
