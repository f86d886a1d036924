"""The app as an LTI 1.3 tool (LTI Advantage): the platforms registered here (``platforms``), the tool's key pair
(``tool_key``), the launch state pylti1p3 keeps in the app's database (``launch_state``), the LMS's members as
students (``members``) and the scores waiting to be posted to a gradebook (``grades``).

The protocol itself (OIDC login, id_token checks, the service tokens, deep-linking and AGS messages) is
pylti1p3's; these modules give it what it asks of a framework: where registrations, keys and state live.
"""
