"""Case files: every TOML/JSON schema onbottom reads, and every case → model builder.

One module per file type; each holds the strict schema (:class:`onbottom._casefile.StrictModel`
tables: unknown keys, wrong types and values out of range are errors naming the key, the file
and the line), the cross-checks between tables, and the builder that turns a parsed case into
the plain value types and models of the packages below (``inputs``, ``soil``, ``hydro``,
``dynamics``, ``study``, ``assess``, ``reliability``, ``dem``). The library's API takes those
built objects; only this package and ``cli`` read case files.

* :mod:`~onbottom.cases.stability` — ``onbottom stability`` / ``loads`` (DNV-RP-F109 checks);
* :mod:`~onbottom.cases.storm` — ``onbottom storm`` (storm section), shared by the pipeline,
  curves, reliability and route cases;
* :mod:`~onbottom.cases.section` — ``onbottom simulate`` (centrifuge section programmes).
* :mod:`~onbottom.cases.assess` — ``onbottom assess`` (a route → ``assess.Route``).
* :mod:`~onbottom.cases.reliability` — ``onbottom reliability`` (→ ``ReliabilitySetup``).
* :mod:`~onbottom.cases.programme` — load-programme tables and files (TOML, CSV) of ``simulate``.
* :mod:`~onbottom.cases.force` — a case's ``[hydro]`` table → a force model (storm-type cases).
* :mod:`~onbottom.cases.dem` — DEM config files (JSON) of ``onbottom dem`` and ``dem-lammps``.
* :mod:`~onbottom.cases.pipeline` — ``onbottom storm`` with a ``[pipeline]`` table (pipeline FE).
* :mod:`~onbottom.cases.curves` — ``onbottom curves`` (generalized-stability curves grid);
* :mod:`~onbottom.cases.sweep` — ``onbottom sweep`` (grid files of registered functions);

Submodules are imported when used (``import onbottom.cases`` stays light).
"""
