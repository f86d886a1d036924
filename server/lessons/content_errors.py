"""The error of a content file (a scene, a table) that does not resolve."""


class ContentError(ValueError):
    """A scene file that does not resolve; the message names the file, the variant and the slider."""
