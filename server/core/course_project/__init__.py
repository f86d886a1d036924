"""The course project of a TMM course (Chaika–Vasylenko §3.4): its sheets as pure numeric core functions."""
