"""OpenAPI covers the multi-run API; the flat endpoints are documented by upstream's protocol."""


def only_api_paths(endpoints):
    return [endpoint for endpoint in endpoints if endpoint[0].startswith("/api/")]
