# Same install and start commands as README.md ("Start the app").
FROM python:3.11-slim
WORKDIR /app
COPY . .
RUN python3 -m pip install -e .
RUN python3 -m server.core.warm_up
EXPOSE 8000
CMD ["python3", "-m", "server", "--host", "0.0.0.0", "--port", "8000"]
