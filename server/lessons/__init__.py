"""The lesson model: scenes, their sliders, variants and questions as read from content/ (scenes.py), and the
request body a scene page sends for given slider values (requests.py). No web code: the HTTP layer
(server/api) and the classroom (server/classroom) both build on it."""
