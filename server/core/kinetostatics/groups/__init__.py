"""Kinetostatics of a general mechanism by structural groups (Chaika–Vasylenko §3.1, generalised): the groups
in reverse order of attachment, then the input crank; friction by successive approximations (3.3)."""
