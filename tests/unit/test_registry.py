def test_snapshot_of_an_unloaded_registry_keeps_the_builtin_entries():
    """A snapshot taken before the first look-up still holds the built-in entries, so a
    restore after a test's own registrations leaves the registry as a user would find it."""
    from dataclasses import dataclass

    from onbottom.registry import Registry

    @dataclass(frozen=True)
    class Entry:
        name: str
        description: str = "test"
        options: None = None

    reg: Registry[Entry] = Registry("thing", "things", loader=lambda: reg.add(Entry("builtin")))
    saved = reg.snapshot()
    assert list(saved) == ["builtin"]
    reg.add(Entry("extra"))
    reg.restore(saved)
    assert reg.names() == ("builtin",)
