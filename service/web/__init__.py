"""Browser pages of the service and the plot routes (``beltstudy.service.web.routes.router``).

The pages are static shells; a small script (``static/app.js``) fills them from the JSON API
with the bearer token the user typed (kept in ``sessionStorage``), and never through
``innerHTML``. Plots are matplotlib figures from :mod:`beltstudy.service.charts` served as PNG or SVG.
"""
