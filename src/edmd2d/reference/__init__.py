"""Brute-force reference engine: the plain event loop, in plain Python.

At every step it examines *every* pair of disks (with all periodic images) and *every*
disk against every wall, box wall and wall end point, takes the earliest contact, moves
*all* disks to that moment, resolves it, and repeats.  It is slow (O(N^2) per event) and
meant to be read: it is the specification of what :class:`edmd2d.Simulation` computes
and the oracle its tests compare against.  It shares no code with the compiled engine;
only the value objects :class:`~edmd2d.Box` and :class:`~edmd2d.Wall` are common, and
the static test of whether a group of slow disks holds itself up (a linear program in
``edmd2d._balance``, tested on its own).

Collisions may be inelastic.  By default the disks are smooth: a collision changes only
the normal component of the relative velocity (of the disk's velocity, at a wall),
which becomes ``-e`` times itself, with a coefficient of restitution ``e`` for each pair
of species and ``e_w`` for all walls.  The kinetic energy lost, ``(1 - e**2)/2 * mu * vn**2`` per
collision with normal velocity ``vn`` and reduced mass ``mu`` (the disk's own mass
against a wall or an immovable disk), is added up in ``dissipated``.  The TC model of
Luding and McNamara (1998) keeps inelastic collapse away: a collision is elastic if one
of its movable disks has collided less than a time ``tc`` before.  With the defaults
(``e = e_w = 1``) every collision is elastic.

Under uniform gravity ``g`` every movable disk flies on a parabola,
``x(t) = x0 + v0 t + g t^2 / 2``, while immovable disks and walls feel nothing.  Contact
times are then roots of polynomials of degree up to four, found here by a method of
their own: :func:`numpy.roots` on the derivative cuts time into pieces on which the
contact function is monotonic, and its sign, followed by Newton's method and bisection,
locates the crossing.

Under gravity, disks may come to rest (``resting``): a slow disk held by static bodies
stops being moved until an impact, a support leaving or a thermostat wakes it, by
the rules of :class:`edmd2d.physics.Resting`, written out plainly in ``_resting.py``.

Under shear (``shear_rate``), a box periodic on both axes has Lees-Edwards
(sliding-brick) boundaries: the images of the box above slide along x at ``shear_rate *
height``, those below the other way, and a disk leaving through the top or the bottom
comes back as its image, with that image's velocity.  The search tries the sliding
images, and the collision rules act on them, as on any periodic image; tallies of the
collisional virial and of the kinetic stress over the flights give the shear stress.

Rough disks (``tangential_restitution``, ``friction``, ``inertia``,
``angular_velocities`` and their ``wall_`` counterparts) also spin: a collision turns
the tangential velocity of the contact points into ``-beta`` times itself, limited by
Coulomb friction, exchanging energy between translation and rotation (``_rough.py``).

Wall segments may move (``wall_motions``): a :class:`~edmd2d.Translation` (a piston,
at a constant velocity over a distance) or an :class:`~edmd2d.Oscillation` (a shaken
segment, ``A sin(omega t + phase)`` along a direction) carries a segment without
turning it.  Against a translation the contact times are those of a fixed segment in
its frame, phase by phase (rest, motion, rest); against an oscillation, conservative
advancement on the gap, which cannot step past a contact, then bisection to the last
float.  A collision reflects the velocity relative to the segment's, and the segment's
work on the disks is tallied (``wall_work``): ``total_energy() + dissipated -
sum(wall_work)`` stays constant.

The code comes in six parts: the contact-time oracles (``_times.py``), the search for
the earliest contact (``_search.py``), the collision rules (``_rules.py``), the rules
of disks at rest (``_resting.py``) and of rough disks (``_rough.py``), and the event
loop with the simulation's state (``_loop.py``).

Examples
--------
>>> import edmd2d as ed
>>> from edmd2d.reference import ReferenceSimulation
>>> ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
...                           radii=1.0, box=ed.Box(10.0, 10.0, periodic=False))
>>> ref.advance(collisions=1).time
0.5
>>> ref.events
[(0.5, 'disk', 0, 1)]
"""

from __future__ import annotations

from ._loop import ReferenceSimulation
from ._times import EPS as EPS
from ._times import INF as INF
from ._times import box_contact_time_accelerated as box_contact_time_accelerated
from ._times import circle_contact_time as circle_contact_time
from ._times import circle_contact_time_accelerated as circle_contact_time_accelerated
from ._times import circle_contact_time_growing as circle_contact_time_growing
from ._times import oscillating_segment_contact_time as oscillating_segment_contact_time
from ._times import segment_contact_time as segment_contact_time
from ._times import segment_contact_time_accelerated as segment_contact_time_accelerated
from ._times import translating_segment_contact_time as translating_segment_contact_time

__all__ = ["ReferenceSimulation"]
