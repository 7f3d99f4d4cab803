"""The rule language: ``rules.lark`` (the grammar), :mod:`.ast` (dataclasses) and :mod:`.parser`."""
