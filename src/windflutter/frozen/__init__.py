"""The seed's frozen-azimuth methods ``pk`` and ``thesis`` (a fenced plug-in).

The thesis's model: one blade (or the rotor) at a frozen azimuth, locked to the nacelle, undeformed,
with Theodorsen strips in the frequency domain; its searches over rotor speed are the p-k tracking
and root finding (``pk``) and the thesis's 8-k search (``thesis``).  The same searches serve the
Goland wing (:mod:`windflutter.frozen.wing`) and the thesis's simple model
(:mod:`windflutter.frozen.simple_model`).

The core (method ``p``: :mod:`windflutter.overspeed` on :mod:`windflutter.system`) never imports this
package; it is reached only through the methods registry (:data:`windflutter.methods.METHODS`, loaded
when a ``pk`` or ``thesis`` case is built) and the commands that run the wing and the simple model.
``tests/test_layers.py`` keeps the fence.
"""
