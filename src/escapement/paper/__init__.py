"""The paper as printed: its equations as printed (:mod:`.printed`) and corrected (:mod:`.corrected`), the
conventions it mixes (:mod:`.conventions`) and its printed axes (:mod:`.printed_axes`), in the model's terms; its
judgement is :mod:`escapement.verdict`. Import the module you need: the package imports none of them.
"""
