"""The paper's layer: its equations as printed (:mod:`.printed`) and as corrected here (:mod:`.corrected`),
and the claims register, which reads the datasets and never simulates: the one rule of the verdict
(:mod:`.vocabulary`), the engine (:mod:`.claims`) and the checks it registers. Import the module you need: the
package imports none of them.
"""
