from enum import StrEnum

class Preset(StrEnum):
    IRB2400 = "irb2400"
    PUMA560 = "puma560"

    def __str__(self) -> str:
        return str(self.value)
