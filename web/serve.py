"""Serves web/www on localhost for the path-tool page.

Plain `http.server` plus two headers that make the page cross-origin isolated
(Cross-Origin-Opener-Policy and Cross-Origin-Embedder-Policy), so that the browser's
`performance.now()` has its fine resolution for the drag-latency measurement, and the
`application/wasm` type that `WebAssembly.instantiateStreaming` requires.

    python3 web/serve.py [--port PORT] [--port-file FILE]

With `--port 0` the system picks a free port; `--port-file` receives the port once the
server listens (for scripts that start it in the background).
"""

import argparse
import functools
import http.server
import os

WWW = os.path.join(os.path.dirname(os.path.abspath(__file__)), "www")


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
    }

    def end_headers(self):
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        self.send_header("Cache-Control", "no-store")
        super().end_headers()

    def log_message(self, format, *args):
        if os.environ.get("KAPPA_WEB_LOG"):
            super().log_message(format, *args)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, default=8000)
    parser.add_argument("--port-file")
    args = parser.parse_args()
    handler = functools.partial(Handler, directory=WWW)
    with http.server.ThreadingHTTPServer(("127.0.0.1", args.port), handler) as server:
        port = server.server_address[1]
        if args.port_file:
            tmp = args.port_file + ".tmp"
            with open(tmp, "w") as f:
                f.write(f"{port}\n")
            os.replace(tmp, args.port_file)
        print(f"kappa path tool: http://127.0.0.1:{port}/", flush=True)
        server.serve_forever()


if __name__ == "__main__":
    main()
