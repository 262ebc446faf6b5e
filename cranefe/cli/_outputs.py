"""Output options shared by the analysis commands: --archive, --vtu, --xdmf, --images."""

import sys


def add_output_arguments(p):
    g = p.add_argument_group("outputs")
    g.add_argument("--archive", metavar="OUT.h5", help="write an HDF5 result archive")
    g.add_argument("--vtu", metavar="OUT.vtu", help="write a ParaView VTU file")
    g.add_argument("--xdmf", metavar="OUT.xdmf", help="write an XDMF series (one step per "
                   "mode)")
    g.add_argument("--images", metavar="DIR", help="render one PNG per mode (off-screen)")
    g.add_argument("--animate", action="store_true", help="with --images: a GIF per mode")
    g.add_argument("--image-size", metavar="WxH", default="1024x768",
                   help="image size in pixels (default 1024x768)")


def _size(text):
    from ..errors import ModelError
    try:
        w, h = (int(v) for v in text.lower().split("x"))
        if w < 16 or h < 16:
            raise ValueError
    except ValueError:
        raise ModelError(f"--image-size {text!r}: give WIDTHxHEIGHT in pixels, e.g. "
                         "1024x768") from None
    return w, h


def write_outputs(args, model, system, results, modal):
    """Write what the options ask for; report each path on stderr."""
    written = []
    if args.animate and not args.images:
        from ..errors import ModelError
        raise ModelError("--animate needs --images DIR")
    if args.archive:
        from ..outputs import archive
        written.append(archive.write(args.archive, model, system, results,
                                     command=["cranefe"] + args.argv,
                                     timings=modal.timings))
    if args.vtu:
        from ..outputs.paraview import write_vtu
        written.append(write_vtu(args.vtu, model, system.dofs, modal))
    if args.xdmf:
        from ..outputs.paraview import write_xdmf_modes
        written.append(write_xdmf_modes(args.xdmf, model, system.dofs, modal))
    if args.images:
        from ..outputs.render import render_modes
        written += render_modes(args.images, model, system.dofs, modal,
                                size=_size(args.image_size), animate=args.animate)
    for path in written:
        print(f"wrote {path}", file=sys.stderr)
    return written
