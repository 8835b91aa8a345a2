"""A compiled loop kernel's call to another, through the other's address: each compiled once.

numba compiles a call from one jitted function to another by linking the callee's code into
the caller's module, where LLVM optimises it again (it may inline it) and generates its machine
code again. A kernel that calls others pays for them twice that way, and their callees three
times: the step's kernel (engine.pipeline.game_loop's ``step_loop``, which calls the solver and
the contacts, which call the manifolds) took 8.7 s of a cold compile of its own, where it takes
5.1 s calling them as below; the contacts' kernel no longer carries the manifolds' code.

So a kernel that calls another (``engine.kernels._calling_compiled``) calls it here instead:
a numba intrinsic whose code loads the callee's address from a slot (a pointer in memory, named
by the callee, ``SYMBOL`` + its name, which LLVM's dynamic linker finds by that name) and calls
it by numba's own calling convention, exceptions and all, so the callee's code is generated
once, in its own module. The slot is named before any caller is compiled or loaded from numba's
cache (its object code names it), holds numba's "unresolved symbol" function until the callee
is compiled or loaded (a call then raises RuntimeError, never jumps to nowhere), and then the
callee's address.

The slot holds one address, that of the callee compiled for its sample's argument types
(``engine.kernels.loop(sample=...)``), which is what every caller passes: a caller that passes
other types does not compile, and the message names both. (A specialisation per caller would
compile in play; the kernels are built not to.)
"""

from __future__ import annotations

import ctypes
from typing import Any

__all__ = ["SYMBOL", "calling", "fill"]

#: The prefix of a slot's name, before the called kernel's name.
SYMBOL = "engine.kernel_calls."

#: Each slot made so far, by the name of the kernel whose address it holds.
_SLOTS: dict[str, ctypes.c_void_p] = {}
#: Each called kernel's intrinsic (one for all its callers).
_CALLS: dict[str, Any] = {}


def _slot(name: str) -> ctypes.c_void_p:
    """The slot of the kernel ``name``, made and told to LLVM's dynamic linker the first time:
    it holds numba's function for an unresolved symbol (it raises RuntimeError) until
    ``fill``."""
    if name not in _SLOTS:
        import llvmlite.binding as ll
        from numba.core.registry import cpu_target
        from numba.core.runtime import rtsys

        rtsys.initialize(cpu_target.target_context)  # (its functions compiled, once)
        unresolved = rtsys.library.get_pointer_to_function("nrt_unresolved_abort")
        slot = ctypes.c_void_p(unresolved)
        ll.add_symbol(SYMBOL + name, ctypes.addressof(slot))
        _SLOTS[name] = slot
    return _SLOTS[name]


def fill(k: Any) -> None:
    """Put the address of kernel ``k`` compiled for its sample's argument types in its slot,
    if a caller has one made (it is compiled, or loaded from the cache, already)."""
    slot = _SLOTS.get(k.name)
    if slot is None:
        return
    cres = k.fast.overloads[k.sample_types()]
    slot.value = cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name)


def calling(k: Any) -> Any:
    """What a compiled kernel calls in place of kernel ``k`` (an engine.kernels.LoopKernel): an
    intrinsic that types as ``k`` compiled for its sample's argument types
    (``k.sample_types()``), and calls it through its slot."""
    if k.name in _CALLS:
        return _CALLS[k.name]
    from numba.core import cgutils, errors, types
    from numba.extending import intrinsic

    name = k.name
    _slot(name)
    if k.ready:  # (compiled or loaded before any caller was made)
        fill(k)

    def typer(typingctx: Any, *args: Any) -> Any:
        given = tuple(types.unliteral(a) for a in args)
        expected = k.sample_types()
        if given != expected:
            diff = [
                f"argument {i}: {g}, not {e}"
                for i, (g, e) in enumerate(zip(given, expected, strict=False))
                if g != e
            ]
            if len(given) != len(expected):
                diff.append(f"{len(given)} arguments, not {len(expected)}")
            raise errors.TypingError(
                f"a kernel calls {name} with argument types other than its sample's "
                f"({'; '.join(diff)}): a kernel called from another is compiled once, for "
                f"its sample's types (engine.kernel_calls)"
            )
        k.fast.compile(expected)
        fill(k)
        cres = k.fast.overloads[expected]
        restype = cres.signature.return_type
        sig = restype(types.StarArgTuple.from_types(expected))

        def codegen(context: Any, builder: Any, sig: Any, llargs: Any) -> Any:
            from llvmlite import ir

            fnty = context.call_conv.get_function_type(restype, expected)
            symbol = SYMBOL + name
            try:
                slot = builder.module.get_global(symbol)
            except KeyError:
                slot = ir.GlobalVariable(builder.module, ir.IntType(8).as_pointer(), symbol)
                slot.linkage = "external"
            fn = builder.bitcast(builder.load(slot), fnty.as_pointer())
            values = [builder.extract_value(llargs[0], i) for i in range(len(expected))]
            status, result = context.call_conv.call_function(builder, fn, restype, expected, values)
            with cgutils.if_unlikely(builder, status.is_error):
                context.call_conv.return_status_propagate(builder, status)
            return result

        return sig, codegen

    typer.__name__ = f"call_{k.py.__name__}"
    _CALLS[name] = intrinsic(typer)
    return _CALLS[name]
