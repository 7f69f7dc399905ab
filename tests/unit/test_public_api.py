"""Unit tests: every name the package exports resolves (lazy attributes included)."""

from __future__ import annotations

import pytest

import onbottom


@pytest.mark.parametrize("name", onbottom.__all__)
def test_exported_name_resolves(name):
    assert getattr(onbottom, name) is not None


def test_unknown_attribute_raises():
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        onbottom.nope
