"""The paper as printed: its equations as printed (:mod:`.printed`) and as corrected here (:mod:`.corrected`),
the conventions it mixes (:mod:`.conventions`) and the limits and ticks of its printed axes (:mod:`.printed_axes`),
each written in the model's terms. The judgement of the paper is :mod:`escapement.verdict`. Import the module you
need: the package imports none of them.
"""
