"""The import graph helpers of the layer tests (tests/test_layers.py, test_runtime_layers.py):
strongly connected components of a grimp graph, and the import lines that make one."""

from __future__ import annotations

import grimp


def edges_of(graph: grimp.ImportGraph, skip: tuple[str, ...] = ()) -> dict[str, set[str]]:
    """module -> the modules it imports directly, both outside the packages `skip` names."""

    def kept(module: str) -> bool:
        return not any(module == s or module.startswith(s + ".") for s in skip)

    return {
        m: {i for i in graph.find_modules_directly_imported_by(m) if kept(i)}
        for m in graph.modules
        if kept(m)
    }


def strongly_connected(edges: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles of `edges` (edges_of): its strongly connected components of more than
    one module, each sorted (Tarjan's algorithm, iterative so that a deep chain cannot
    overflow the stack)."""
    edges = {m: sorted(edges[m]) for m in sorted(edges)}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []
    for root in edges:
        if root in index:
            continue
        work = [(root, iter(edges[root]))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in edges:  # outside the graph's packages
                    continue
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(edges[child])))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    out.append(sorted(component))
    return out


def describe(graph: grimp.ImportGraph, component: list[str]) -> str:
    """One cycle of the component, import by import, with the lines that make it."""
    members = set(component)
    lines = []
    for importer in component:
        for imported in sorted(graph.find_modules_directly_imported_by(importer) & members):
            for detail in graph.get_import_details(importer=importer, imported=imported):
                lines.append(
                    f"  {importer} -> {imported} (line {detail['line_number']}: "
                    f"{detail['line_contents']})"
                )
    return "\n".join(lines)
