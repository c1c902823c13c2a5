"""The paper's reference agents: a tool-calling browser loop over screenshots, with either
`sleep(seconds)` or `wait_for(condition, timeout)`, on any OpenAI-compatible model (README.md)."""
