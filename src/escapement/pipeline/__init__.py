"""What the workflow's rules call: configuration, jobs, generated documents. Never imported by
:mod:`escapement` itself."""
