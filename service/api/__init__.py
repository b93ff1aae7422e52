"""The REST API: :func:`beltstudy.service.api.app.create_app` builds the FastAPI application."""
