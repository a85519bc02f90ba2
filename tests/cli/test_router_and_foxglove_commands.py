"""`coopdrive router` and `coopdrive foxglove` name what is wrong in one line instead of a traceback."""

import socket
import subprocess
import sys


def coopdrive(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coopdrive.cli", *args], capture_output=True, text=True, timeout=60)


def test_the_router_names_a_missing_config_file_in_one_line(tmp_path):
    result = coopdrive("router", "--config", str(tmp_path / "zenohd.json5"))
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "zenohd.json5" in result.stderr and ".rs:" not in result.stderr


def test_the_router_names_a_bad_endpoint_in_one_line():
    result = coopdrive("router", "--listen", "tcp/nowhere")
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "--listen tcp/nowhere" in result.stderr


def test_foxglove_on_a_port_in_use_says_so_in_one_line():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        result = coopdrive("foxglove", "--host", "127.0.0.1", "--port", str(taken.getsockname()[1]))
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1 and "cannot serve on 127.0.0.1" in result.stderr
