# Same install and start commands as README.md ("Start the app").
FROM python:3.11-slim
WORKDIR /app
COPY . .
RUN python3 -m pip install -e .
RUN python3 -m server.core.warm_up
EXPOSE 8000
# Behind a reverse proxy, name its address as the container sees it, or every student counts as the proxy:
#   docker run -e MDL_FORWARDED_ALLOW_IPS=172.17.0.1 -e MDL_DATABASE_URL=postgresql://… (README, deploy/)
CMD ["python3", "-m", "server", "--host", "0.0.0.0", "--port", "8000"]
