"""A Ctrl-C that arrives while a computation runs is a KeyboardInterrupt, even when the result is
the interpreter's first numpy array made by the extension (issue 37). rust-numpy loads numpy's C
API lazily, by running Python code; a pending SIGINT raised inside that code made it panic
("Failed to access NumPy array API capsule", a PanicException) until the extension loaded the API
while it is imported."""

import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent(
    """
    import os, signal, threading
    import rotor_chain as rc

    net = rc.Network.ready("kagome")
    # The signal arrives during the free patch's SVD (about 1.5 s in the debug build the tests
    # use), before the extension has made any array in this interpreter.
    threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    try:
        net.null_spaces((12, 12), boundary="free")
        print("finished before the signal")
    except KeyboardInterrupt:
        print("KeyboardInterrupt")
    """
)


def test_a_ctrl_c_before_the_first_array_is_a_keyboard_interrupt():
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=300)
    assert "PanicException" not in done.stderr, done.stderr
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "KeyboardInterrupt", (done.stdout, done.stderr)
