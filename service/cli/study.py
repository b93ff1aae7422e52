"""`beltstudy` sub-commands: placeholder until this module is written."""


def register(sub) -> None:
    return None
