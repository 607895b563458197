"""The one kind of failure rtfarm reports to its user."""


class FarmError(Exception):
    """Bad input or a failed render: printed as one `error: ...` line, exit status 1."""
