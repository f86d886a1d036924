"""Classroom assignments: the instructor's specification, per-student variants and their storage.
No web code: the API layer (server/api/routers/assignments.py) validates requests and calls this."""
