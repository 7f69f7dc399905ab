"""onbottom.peers — other programs solving the same problems, for standing comparisons.

:mod:`onbottom.peers.opensees`: the pipeline FE problem built in OpenSeesPy (optional extra
``onbottom[peers]``). Validation: docs/validation/opensees_peer.md.
"""
