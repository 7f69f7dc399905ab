"""Report sections: one module per section, each registering itself with ``@section``."""
