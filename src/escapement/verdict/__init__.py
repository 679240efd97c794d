"""The verdict: each claim of the paper checked on the replication's datasets, by one rule. It reads datasets
and never simulates: it imports only the model and the paper as printed (a test holds it to that).

:mod:`.engine` runs each claim's check (``claims.yaml`` says what a claim holds) under each reading, :mod:`.rule`
gives the row's status and :mod:`.tally` the findings'; one module of checks per part of the paper.
"""
